#pragma once
// The Richard-Germay-Detournay bit-rock law with the state-dependent cut delay t_n (DESIGN.md §3, chapter seed
// 2.28-2.33), shared by the kinds whose bit drills: axial_torsional (wave strings) and lumped_axial_torsional.
//   t_n: Phi(t) - Phi(t - t_n) = 2 pi / n,  d = n (U(t) - U(t - t_n))   (from the stored bit angle and position;
//        after a bounce, against the deepest of the last four blade passes at that angle, or, with
//        rock/surface_passes = 1, literally against the previous blade pass even if it passed in the air)
//   cutting (d > 0, not turning backwards): W_c = a zeta eps d, T_c = a^2 eps d / 2
//   wear-flat contact (d > 0): W_f = a sigma l advancing, in [0, a sigma l] held axially, 0 lifting
//   friction: T_f = a gamma mu W_f / 2 sign(w), set-valued at w = 0 (stuck while the torque stays within T_c + T_f)
//   off bottom (d <= 0): no contact at all.
//   Optional rock strength heterogeneity: eps and sigma l both times 1 + g(U), g a seeded random field of the drilled
//   depth U (the bit's axial position; StrengthHeterogeneity).
//   Optional Stribeck friction: mu(w) = mu + (mu_s - mu) exp(-|w| / w_s) while turning; a stuck bit holds with mu_s.
//   Optional contact law (contact_law.hpp, chapter 2.29-2.30, 2.33): mu F(|w|) in place of mu, a stuck bit holding with
//   mu F(0+) (nothing for a smooth F); with eq. 2.33 also the cutting torque times F(|w|)^2.
// Three pieces: RgdLaw (parameters and forces), CutProfile (the bit's stored angle and position and the search for
// t_n and d) and RgdRegimes (rotation forward / stuck / backward, axial advancing / held / lifting, contact on / off,
// switched at located events). The string that drives the bit is the caller's.
#include <algorithm>
#include <cmath>
#include <limits>

#include "drillwave/bitrock/contact_law.hpp"
#include "drillwave/bitrock/heterogeneity.hpp"
#include "drillwave/bitrock/roughness.hpp"
#include "drillwave/bitrock/stick_slip.hpp"
#include "drillwave/integration/hermite_history.hpp"
#include "drillwave/integration/options.hpp"

namespace drillwave::bitrock {

enum class Axial { kAdvancing, kHeld, kLifting };

// Forces at the bit for one state: what the string drives it with and what the rock answers.
struct RgdForces {
  double depth = 0, tn = 0;
  double drive_torque = 0, drive_force = 0;  // from the string (and gravity) on the bit at its current speeds
  double torque = 0, weight = 0;             // the rock's reaction while moving (slip values)
  double cut_weight = 0;
  // Held axially, how far the bit is from lifting: the net force on the wear flats (drive force less the cut weight),
  // or, where a stuck bit's cutters answer what presses them (RgdLaw::OnBottom), the drive force itself: such a bit
  // lifts only when the string pulls it up.
  double lift_margin = 0;
  double static_forward = 0, static_backward = 0;  // torque the contact can hold at rest

  AtRest RotationAtRest() const { return {drive_torque, {static_forward, static_backward}}; }
};

struct RgdLaw {
  double a = 0, zeta = 0, eps = 0, sigma_l = 0, mu = 0, gamma = 0;
  int blades = 4;
  // The rock surface under a blade is the deepest position of the last surface_passes blade passes at that angle.
  // 4 (default): after a bounce the rock is where a blade last cut. 1: RGD's d = n (U(t) - U(t - t_n)) taken
  // literally, the previous blade's position even if it passed in the air (a bouncing bit then drifts upwards).
  int surface_passes = 4;
  double static_mu = 0, stribeck_speed = 0;  // Stribeck friction (stribeck_speed 0: Coulomb, static_mu = mu)
  ContactLaw contact_law;  // the chapter's friction function F of the flats (default: RGD's sign); not with Stribeck
  BottomRoughness bottom_roughness;  // of the rock surface the blades left before t = 0 (default: smooth)
  StrengthHeterogeneity strength_heterogeneity;  // of eps and sigma l along the drilled depth (default: homogeneous)

  double ContactForce() const { return a * sigma_l; }  // a sigma l, of the homogeneous rock
  // a sigma l (1 + g(z)) of the rock at drilled depth z (ContactForce() exactly when homogeneous).
  double ContactForceAt(double z) const { return ContactForce() * strength_heterogeneity.Multiplier(z); }
  // Friction coefficient of the wear flats at bit speed w (Stribeck: decays from static_mu to mu; a contact law: mu F).
  double MuAt(double w) const {
    if (contact_law.has_function()) return mu * contact_law.F(w);
    return stribeck_speed > 0 ? mu + (static_mu - mu) * std::exp(-std::abs(w) / stribeck_speed) : mu;
  }
  // d MuAt / d w at w > 0: the slope a Stribeck law or a contact law's F puts into the linearization.
  double MuSlope(double w) const {
    if (contact_law.has_function()) return mu * contact_law.Slope(w);
    return stribeck_speed > 0 ? -(static_mu - mu) / stribeck_speed * std::exp(-w / stribeck_speed) : 0.0;
  }
  // The coefficient a stuck bit holds with.
  double StaticMu() const { return contact_law.has_function() ? mu * contact_law.AtRest() : static_mu; }
  double FrictionArm(double w) const { return 0.5 * a * gamma * MuAt(w); }  // T_f = arm * W_f while turning
  double StaticFrictionArm() const { return 0.5 * a * gamma * StaticMu(); }  // the most a stuck bit holds
  double CutWeightPerDepth() const { return a * zeta * eps; }               // W_c / d
  double CutTorquePerDepth() const { return 0.5 * a * a * eps; }            // T_c / d
  // Steady drilling under weight on bit W0 at bit speed w: depth of cut per blade, torque on bit.
  double SteadyDepth(double wob) const { return std::max(0.0, (wob - ContactForce()) / CutWeightPerDepth()); }
  // The depth of cut per revolution under weight W0 held on the rock at drilled depth z (no axial dynamics): the
  // cutters carry what the wear flats' contact a sigma l (1 + g(z)) leaves of W0, so a stronger rock is cut less deep
  // and the weight stays W0 (SteadyDepth(wob) exactly when homogeneous).
  double HeldWeightDepth(double wob, double z) const {
    const double strength = strength_heterogeneity.Multiplier(z);
    return std::max(0.0, (wob - ContactForce() * strength) / (CutWeightPerDepth() * strength));
  }
  // The cutting torque per depth of cut of a bit turning at w (eq. 2.33 fades it by F(|w|)^2).
  double CutTorquePerDepthAt(double w) const { return contact_law.CutTorque(CutTorquePerDepth(), w); }
  double SteadyTorque(double wob, double w) const {
    return CutTorquePerDepthAt(w) * SteadyDepth(wob) + FrictionArm(w) * ContactForce();
  }
  // d T / d w of steady drilling under wob at bit speed w > 0, the depth of cut held (0 for Coulomb friction and RGD's
  // cutting torque): the slope the friction law (and eq. 2.33's cutting torque) puts into the linearization.
  double SteadyTorqueSlope(double wob, double w) const {
    return 0.5 * a * gamma * MuSlope(w) * ContactForce() +
           contact_law.CutTorqueSlope(CutTorquePerDepth() * SteadyDepth(wob), w);
  }
  // The rock's answer to a bit on bottom (f.drive_force and f.depth set): turning w (0 when stuck), cutting into new
  // rock or not (turning backwards, or not yet back past the furthest angle reached), the bit at drilled depth z (its
  // axial position U: where the rock's strength is read).
  void OnBottom(Turn turn, Axial axial, double w, bool cutting, double z, RgdForces& f) const;
};

// The bit's stored angle and position (prehistory: steady drilling Phi = Omega0 t, U = V0 t + h(Omega0 t) over the
// bottom's roughness h) and the depth of cut against the rock surface under the blades.
class CutProfile {
 public:
  CutProfile(int blades, double omega0, double rop0, int surface_passes = 4, const BottomRoughness& roughness = {});
  // The depth of cut against the rock surface under the blades: the deepest position any of the last surface_passes
  // blades reached at the present angle phi. After a bounce the previous blade may have passed in the air; the rock is where
  // a blade last cut, not where the previous one happened to be (with continuous contact since the previous blade
  // passed, it is the deepest, and d = n (U(t) - U(t - t_n)) as in RGD). The cut delay t_n is returned through tn.
  // The search starts from the t_n of the last committed step end, so that no evaluation depends on the ones before
  // it (trial stages, samples).
  double DepthOfCut(double phi, double u, double t, integration::Side side, bool contact, double last_contact_change,
                    double* tn = nullptr) const;
  // Appends the accepted piece (angle and position at the state's indices), and forgets what lies further back than
  // `keep` seconds and twenty cut delays.
  void Commit(const integration::Piece& p, int phi_index, int u_index, bool contact, double last_contact_change,
              double keep);
  // The furthest angle the bit has reached before t: no new rock is cut before the bit is back past it. (Outputs
  // sampled inside the last committed piece compare with the furthest angle before that piece.)
  double Furthest(double t) const { return t < last_end_ ? phi_max_before_ : phi_max_; }
  double committed_cut_delay() const { return tn_committed_; }

 private:
  double TimeAngleBehind(double phi, double t, integration::Side side, double back, double guess) const;

  int blades_, surface_passes_;
  double omega0_;
  integration::HermiteHistory history_;
  double phi_max_ = 0, phi_max_before_ = 0, last_end_ = 0;
  double tn_committed_ = 0;  // t_n at the end of the last committed piece: where the next searches start
};

// The bit's discrete regimes and their switching. The witnesses are the integration loop's: 0 rotation, 1 rotation
// (second margin while stuck), 2 axial, 3 axial (second margin), 4 contact. `forces()` evaluates the bit's forces at
// the state in the present regimes, `depth()` its depth of cut; w and v are the state's bit speeds.
struct RgdRegimes {
  static constexpr int kWitnesses = 5;
  Turn turn = Turn::kForward;
  Axial axial = Axial::kAdvancing;
  bool contact = true;
  double last_contact_change = -std::numeric_limits<double>::infinity();

  double BitSpeed(double w) const { return turn == Turn::kStuck ? 0.0 : w; }
  bool AxiallyHeld() const { return axial == Axial::kHeld && contact; }

  template <class ForcesAt, class DepthAt>
  double Witness(int k, double w, double v, double contact_force, const ForcesAt& forces, const DepthAt& depth) const {
    switch (k) {
      case 0:
      case 1:
        return TurnWitness(turn, k, w, [&] { return forces().RotationAtRest(); });
      case 2:
      case 3: {
        if (!contact) return 1.0;
        if (axial == Axial::kAdvancing) return k == 2 ? v : 1.0;
        if (axial == Axial::kLifting) return k == 2 ? -v : 1.0;
        const RgdForces f = forces();  // held: the net force must stay within [0, a sigma l]
        const double net = f.drive_force - f.cut_weight;
        return k == 2 ? contact_force - net : f.lift_margin;
      }
      case 4: {
        // 1 nm of hysteresis: right after a landing (or lift-off) the depth of cut is zero to rounding, and the cut
        // delay's root finding may place it on either side; without it the contact would chatter.
        constexpr double kHysteresis = 1e-9;
        const double d = depth();
        return contact ? d + kHysteresis : kHysteresis - d;
      }
    }
    return 1.0;
  }

  // Applies event k at time t; w and v are the state's bit speeds (zeroed where the bit sticks or is held). True if a
  // regime changed.
  template <class ForcesAt>
  bool OnEvent(int k, double t, double& w, double& v, double contact_force, const ForcesAt& forces) {
    const Turn turn_before = turn;
    const Axial axial_before = axial;
    const bool contact_before = contact;
    if (k == 4) {
      contact = !contact;
      last_contact_change = t;
      if (!contact) {  // lift-off: no contact forces; both motions free
        if (turn == Turn::kStuck) turn = forces().drive_torque >= 0 ? Turn::kForward : Turn::kBackward;
        axial = v >= 0 ? Axial::kAdvancing : Axial::kLifting;
      } else {
        axial = v > 0 ? Axial::kAdvancing : Axial::kLifting;
      }
    } else if (k <= 1) {
      turn = TurnAfterEvent(turn, k, [&] {
        w = 0;
        turn = Turn::kStuck;
        return forces().RotationAtRest();
      });
      if (turn == Turn::kStuck) w = 0;
    } else {
      if (axial == Axial::kHeld) {
        axial = k == 2 ? Axial::kAdvancing : Axial::kLifting;
      } else {
        v = 0;
        axial = Axial::kHeld;
        const RgdForces f = forces();
        const double net = f.drive_force - f.cut_weight;
        if (net > contact_force) axial = Axial::kAdvancing;
        else if (net < 0) axial = Axial::kLifting;
      }
      if (axial == Axial::kHeld) v = 0;
    }
    return turn != turn_before || axial != axial_before || contact != contact_before;
  }
};

}  // namespace drillwave::bitrock
