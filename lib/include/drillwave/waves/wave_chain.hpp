#pragma once
// One wave channel of a string as a chain of pieces (DESIGN.md §1), for kinds whose ends carry inertia and whose
// waves are stored as history rather than followed as breakpoints (the coupled axial-torsional kind: its torsional
// channel, angular speed and torque, and its axial channel, speed down positive and force).
//
// Pieces k = 0..m-1 lie between nodes k and k+1: node 0 is the top, node m the bit; pieces differ in impedance and
// travel time where sections change (pipe, BHA). The internal nodes are massless: the distributed viscous damping and
// the buoyant weight of each piece are lumped at its nodes (half at each end), so the d'Alembert reduction stays exact
// inside every piece. A piece carries the force S = Z (D - U) onto its lower node; a node feels sum Z (2 w_in - v)
// from its pieces. Options on the internal nodes: Coulomb friction against the borehole (side friction, set-valued at
// rest), and Kelvin-Voigt damping (chapter eqs. 2.20, 2.24) as a dashpot eta K / length across each piece, which ties
// the massless nodes into a tridiagonal system (HeldNodes; with side friction too a convex problem).
//
// Each node keeps the history of the two waves it sends (U_{j-1} up into piece j-1, D_j down into piece j). An
// internal node's waves are algebraic in the waves arriving at it; where a kink, a jump or a jump of curvature arrives
// within a step (an event's, an imposed end speed's, the start's out of the steady prehistory; passed on from node to
// node) they are stored in parts split at it, so that every stored quartic passes the error check and a jump stays a
// jump. Those that reach the top or the bit are reported, for the caller to stop its steps there. (A curvature jump is
// looked for where an end's piece restarts, after an event or a breakpoint, and at every split.)
#include <array>
#include <cstddef>
#include <vector>

#include "drillwave/integration/hermite_history.hpp"
#include "drillwave/waves/held_nodes.hpp"

namespace drillwave::waves {

// Whether a kink that reaches an end at kink_time is passed with the breakpoint at t: within a nanosecond per second
// of run time of it. Paths through pieces of nearly equal travel time (a BHA's pieces beside the pipe's) arrive a few
// 1e-11 s apart; a breakpoint at each cost a step that short and the ramp back to the natural step (issue 33: a
// collared string at tolerance 1e-3 spent 1e8 evaluations on such pairs before t = 20 s, a pair every 5 us).
bool PassedWith(double kink_time, double t);

// The chain's constant data: per piece impedance, travel time and Kelvin-Voigt dashpot; per node the ground dashpot,
// the constant load (buoyant weight, axial) and the Coulomb friction level (torsion).
struct ChainSpec {
  std::vector<double> z, tau;   // per piece
  std::vector<double> kv;       // per piece: Kelvin-Voigt dashpot eta K / length across it (empty: none)
  std::vector<double> damping;  // per node (ground dashpot)
  std::vector<double> load;     // per node (constant force: buoyant weight, axial only)
  std::vector<double> coulomb;  // per node (Coulomb friction level against the borehole, torsion only)

  int pieces() const { return static_cast<int>(z.size()); }
  bool kelvin_voigt() const { return !kv.empty(); }
  double ShortestPiece() const;
  double LongestPiece() const;
  double travel_time() const;
};

// The speeds of the chain's two end nodes (or their accelerations) at one instant.
struct ChainEnds {
  double top, bit;
};

class WaveChain {
 public:
  using Side = integration::Side;
  // An end whose speed is algebraic (a massless end balancing the string's force against its own), for chains without
  // Kelvin-Voigt dashpots (with them the ends' speeds and the inner nodes' are one system, which the caller solves
  // with EndSlopes): from the string's force on the end at rest (the waves arriving there), its speed; from that
  // force's rate and the speed, the speed's rate. Prepare then ignores StepEnds' speeds and rates of that end.
  class EndClosure {
   public:
    virtual ~EndClosure() = default;
    virtual double Speed(double t, Side side, double force_at_rest) const = 0;
    virtual double Rate(double t, Side side, double speed, double force_rate_at_rest) const = 0;
  };
  // Steady motion: every node at speed v, the bit node loaded by bit_force (torque on bit, or weight on bit); each
  // piece carries the force that balances the nodes below it.
  WaveChain(const ChainSpec& spec, double v, double bit_force);

  const ChainSpec& spec() const { return spec_; }
  // Closes the ends whose closure is not nullptr (kept by the caller; no Kelvin-Voigt dashpots).
  void CloseEnds(const EndClosure* top, const EndClosure* bit);
  // What the top node supplies in that steady motion (the force on the top piece plus the top node's damping, less
  // its load).
  double steady_top_force() const { return steady_top_force_; }

  // Forces of the string on the top node and on the bit node at the given end speeds, with the end nodes' own share
  // of damping and load.
  ChainEnds EndForces(double t, Side side, ChainEnds speeds) const;
  // One of them: without Kelvin-Voigt dashpots it reads only the wave arriving at that end (the other end's speed
  // does not matter then).
  double TopForce(double t, Side side, ChainEnds speeds) const;
  double BitForce(double t, Side side, ChainEnds speeds) const;
  // The up-going wave arriving at the top at t and its rate: what a wave-cancelling drive absorbs (without Kelvin-Voigt
  // dashpots the string's whole say at the top).
  struct Wave {
    double value, rate;
  };
  Wave TopArrival(double t, Side side) const;

  // EndForces is affine in the end speeds (without side friction): its constant slopes, for ends whose speed is
  // algebraic (a massless end balances the string's force against its own). Without Kelvin-Voigt dashpots the two
  // ends do not feel each other's speed at once (top_bit = bit_top = 0). NaN with side friction.
  struct EndSlopes {
    double top_top, top_bit, bit_top, bit_bit;
  };
  const EndSlopes& end_slopes() const { return end_slopes_; }
  // The rates of EndForces for the end speeds and their rates (the loads are constant).
  ChainEnds EndForceRates(double t, Side side, ChainEnds speeds, ChainEnds rates) const;
  // Every node's speed at time t for the given end speeds (node 0 the top, node m the bit).
  void NodeSpeedsAt(double t, Side side, ChainEnds speeds, std::vector<double>& v) const;
  // The energy of the waves in flight at t: each piece holds Z times the integral of D^2 + U^2 over its travel time.
  double WaveEnergy(double t) const;

  // The waves every node sends over the step [t0, t1] (end speeds at t0, a quarter, the middle and t1; end
  // accelerations at t0 and t1), prepared for Commit; returns the largest scaled error of the stored quartics at the
  // quarter point (> 1: the step must be shorter).
  struct StepEnds {
    double t0, t1;
    ChainEnds speed0, rate0, speed_quarter, speed_mid, speed1, rate1;
  };
  double Prepare(const StepEnds& step, double abs_tol, double rel_tol);
  // Appends the prepared step to the node histories, forgets what lies further back than read_back, and adds to
  // end_kinks the times at which the kinks and jumps just stored next to the top and the bit reach them. With
  // Kelvin-Voigt dashpots, which tie the ends to every node at once, the times at which any stored knot reaches any
  // node (the steps stop there, and the nodes' waves need no splitting).
  void Commit(double t0, double t1, double read_back, std::vector<double>& end_kinks);
  // The step's start is not the last committed end (an event or a breakpoint lies between): Prepare computes it.
  void ForgetStart() { start_is_last_end_ = false; }
  // Whether Prepare reads StepEnds::speed0 and rate0 for a step from t0 (else it reuses the last committed end).
  bool ReadsStart(double t0) const { return !(start_is_last_end_ && t0 == last_commit_end_); }

 private:
  struct SplitWaves {  // a node's waves over a step in parts: part q spans time[q]..time[q + 1]
    int node = 0;
    std::vector<double> time, value_left, value_right, rate_left, rate_right, mid;  // limits at the part ends
  };

  integration::HermiteHistory& NodeHistory(int j) { return node_waves_[j]; }
  const integration::HermiteHistory& NodeHistory(int j) const { return node_waves_[j]; }
  static int NodeBlock(int j) { return 2 * j; }

  EndSlopes FindEndSlopes() const;
  double EndForce(int end, double in, double v, double pull) const;
  double Arrival(int j, double t, Side side, bool from_above) const;
  void Arrivals(double t, Side side, double* in, double* rate) const;
  void NodeSpeeds(const double* in, double top, double bit, double* v) const;
  double InternalNodeSpeed(int j, double a, double b) const;
  double InternalNodeRate(int j, double rate_a, double rate_b, double v) const;
  void NodeRates(const double* in_rate, const double* v, double top, double bit, double* dv) const;
  // Kelvin-Voigt: the internal nodes as HeldNodes (speeds, or their rates given the speeds v; held by side friction
  // only where there is some).
  void SolveHeldNodes(const double* in, double top, double bit, const double* v, double* out) const;
  void Outgoing(double t, ChainEnds speeds, const ChainEnds* rates, Side side, double* out, double* rate) const;
  double WaveScale(int b, double abs_tol, double rel_tol) const;
  bool ArrivingKinks(int j, double t0, double t1, double scale, std::vector<double>& times) const;
  void NodeWaves(int j, double t, Side side, double* out, double* rate) const;
  double SplitNodeWaves(int j, double t0, double t1, double abs_tol, double rel_tol);
  void EndKinks(const integration::HermiteHistory& sender, int comp, double tau, double t0, double t1, int b,
                std::vector<double>& end_kinks);

  ChainSpec spec_;
  int m_;
  double steady_top_force_ = 0;
  std::vector<integration::HermiteHistory> node_waves_;  // per node: the two waves it sends
  std::vector<double> out0_, out1_, outm_, outq_, d0_, d1_;  // the prepared step's waves (ends, middle, quarter, rates)
  std::vector<SplitWaves> splits_;  // the prepared step's nodes stored in parts (the first num_splits_)
  std::size_t num_splits_ = 0;
  std::vector<double> split_times_;
  std::array<double, 2> prepared_scale_{};  // abs_tol, rel_tol of the last Prepare
  EndSlopes end_slopes_{};
  const EndClosure* top_closure_ = nullptr;  // CloseEnds'
  const EndClosure* bit_closure_ = nullptr;
  bool start_is_last_end_ = false;          // out0_ and d0_ hold the waves at the end of the last committed step
  bool prepared_restart_ = false;           // the prepared step's start was computed anew (a knot for the histories)
  double last_commit_end_ = 0;
  mutable std::vector<integration::HermiteHistory::Kink> kinks_;
  mutable std::vector<double> arriving_, arriving_rate_, speeds_, speed_rates_;  // scratch
  HeldNodes held_;               // Kelvin-Voigt: the internal nodes' system (empty otherwise)
  bool held_friction_ = false;   // ... with side friction at some node
  mutable std::vector<double> held_rhs_, held_out_;
  mutable std::vector<signed char> held_state_, held_rate_state_;  // the last solution's (a warm start), the rates'
};

}  // namespace drillwave::waves
