#pragma once
// The rotational regime of a contact with set-valued friction (bit on rock, disc on brake, a node of the wave
// network) and its switching, written once for every kind (DESIGN.md §2). A slipping contact turns with its speed; a
// stuck one is held at rest while the torque driving it stays inside the law's static range, and the integrator
// locates each change as the zero of a witness:
//   slipping: witness 0 is the speed in the slip direction (the contact comes to rest), witness 1 stays positive;
//   stuck:    witness 0 is the margin of the driving torque to the forward limit, witness 1 to the backward one
//             (the contact breaks free in that direction).

namespace drillwave::bitrock {

// The integer values are the slip direction: -1 backwards, 0 stuck, +1 forwards.
enum class Turn : int { kBackward = -1, kStuck = 0, kForward = 1 };

// A stuck contact holds any driving torque in [-backward, forward].
struct StaticRange {
  double forward;
  double backward;
};

// The driving torque on a contact held at rest and the static range that may hold it.
struct AtRest {
  double drive;
  StaticRange range;
};

// The regime of a contact at rest under `drive`: stuck inside the static range, else slipping the way it is driven.
// Also the regime after a slipping contact came to rest (it stays, or reverses): evaluate `r` with the contact held
// (speed zero, regime stuck).
inline Turn TurnAtRest(const AtRest& r) {
  if (r.drive > r.range.forward) return Turn::kForward;
  if (r.drive < -r.range.backward) return Turn::kBackward;
  return Turn::kStuck;
}

// Witness k (0 or 1) of a contact in regime `turn` turning at `speed`; `at_rest()` -> AtRest is called only while it
// is stuck (the driving torque costs an evaluation of the forces).
template <class AtRestFn>
double TurnWitness(Turn turn, int k, double speed, const AtRestFn& at_rest) {
  if (turn != Turn::kStuck) return k == 0 ? static_cast<int>(turn) * speed : 1.0;
  const AtRest r = at_rest();
  return k == 0 ? r.range.forward - r.drive : r.drive + r.range.backward;
}

// The regime after witness k of a stuck contact crossed zero: it breaks free in that witness's direction.
inline Turn TurnBreakingFree(int k) { return k == 0 ? Turn::kForward : Turn::kBackward; }

// The regime after witness k of a contact in regime `before` crossed zero. A stuck contact breaks free; a slipping
// one has come to rest and stays or reverses: `hold()` -> AtRest is called only then, and must hold the contact (its
// speed zero, its regime stuck) before it evaluates the driving torque.
template <class HoldFn>
Turn TurnAfterEvent(Turn before, int k, const HoldFn& hold) {
  return before == Turn::kStuck ? TurnBreakingFree(k) : TurnAtRest(hold());
}

}  // namespace drillwave::bitrock
