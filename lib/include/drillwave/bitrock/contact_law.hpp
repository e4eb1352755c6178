#pragma once
// The wear flats' friction as chapter seed section 2.6 writes it (eqs. 2.28-2.33): an adimensional friction function F
// of the bit's velocity in place of the Richard-Germay-Detournay law's sign,
//   T_f = (a^2 / 2) gamma mu sigma l F(||V_b||),   W_f = a sigma l F(||V_b||),
//   F(r) = alpha r / sqrt(r^2 + eps^2)                         (2.29, sqrt_regularized)
//   F(r) = beta (tanh r + gamma1 r / (1 + gamma2 r^2))         (2.30 read with gamma1 r in the numerator, tanh_hump)
//   F(r) = beta (tanh r + gamma1 / (1 + gamma2 r^2))           (2.30 as printed, tanh_hump_printed)
// and optionally the cutting torque of the chapter's ref. [31], T_c = -a^4 F(||V_b||)^2 d (2.33).
//
// Read here as follows (docs/cases.md says the same):
// - ||V_b|| is the bit's angular speed |w| in rad/s taken as a pure number (F's reference speed 1 rad/s), as the
//   torsional kinds take the same laws (friction.hpp). The chapter's V_b = (U_t, Phi_t) puts m/s beside rad/s; weighed
//   by the bit radius, a |w| is the wear flats' sliding speed, beside which the rate of penetration (1.3e-2 m/s against
//   0.68 m/s at the baseline's 60 rpm) moves the norm by 2e-4. Where it would matter, near rest, the axial speed is the
//   flats' normal motion, not sliding: it orients no friction in their plane, and in a norm it would keep F > 0 on a
//   bit that stops turning, making F(||V_b||) sign w jump at w = 0 again.
// - F replaces the sign in the friction torque only: T_f = (a gamma / 2) mu F(|w|) W_f sign w, with W_f RGD's
//   unilateral axial contact (a sigma l advancing, in [0, a sigma l] held, 0 lifting). Taken literally, W_f = a sigma
//   l F would unload the flats of a bit that turns slower than eps; one creeping under a torque between T_c and
//   T_c + T_f keeps F = (torque - T_c) / T_f in (0, 1) whatever eps, so eps -> 0 would not give RGD's set-valued
//   contact back. With alpha = 1 the two readings agree wherever |w| >> eps.
// - Eq. 2.33's a^4 leaves the units unbalanced and its minus sign is the chapter's orientation of a reaction: read as
//   RGD's cutting torque faded by F^2, T_c = (a^2 eps / 2) d F(|w|)^2 (the same at F = 1), still only while cutting.
// F(0+) is 0 for the smooth laws: a stuck bit then holds no friction, only the cutting torque [0, T_c] (nothing with
// eq. 2.33's cutting torque, so the bit's rotation is smooth). tanh_hump_printed has F(0+) = beta gamma1 and holds
// with it, as RGD holds with F = 1.
#include <optional>

#include "drillwave/bitrock/friction.hpp"

namespace drillwave::bitrock {

// The cutting torque: RGD's a^2 eps d / 2, or eq. 2.33's, the same times F(|w|)^2.
enum class CuttingTorque { kRgd, kFrictionSquared };

class ContactLaw {
 public:
  // RGD's set-valued contact: F = 1 while turning, any value in [-1, 1] at rest.
  ContactLaw() = default;
  // F(r) = f.SlipTorque(r) for r >= 0: f a sqrt_regularized, tanh_hump or tanh_hump_printed law of unit amplitude.
  // Throws std::invalid_argument for another law or amplitude.
  ContactLaw(const FrictionLaw& f, CuttingTorque cutting);

  bool has_function() const { return f_.has_value(); }  // false: RGD's sign
  // F(|w|) of a turning bit (RGD: 1), its slope dF/dr at r = |w| (RGD: 0), and F(0+), the most a stuck bit holds with.
  double F(double w) const;
  double Slope(double w) const;
  double AtRest() const;
  // The cutting torque t_c of RGD as this law has it on a bit turning at w, and on a stuck one (at F(0+)).
  double CutTorque(double t_c, double w) const;
  double CutTorqueAtRest(double t_c) const;
  // d CutTorque / d w at w > 0: t_c 2 F F' with eq. 2.33, else 0.
  double CutTorqueSlope(double t_c, double w) const;
  // The factor CutTorque(t_c, w) / t_c.
  double CutFactor(double w) const { return fades_cutting() ? F(w) * F(w) : 1.0; }
  bool fades_cutting() const { return cutting_ == CuttingTorque::kFrictionSquared; }
  const std::optional<FrictionLaw>& function() const { return f_; }

 private:
  std::optional<FrictionLaw> f_;
  CuttingTorque cutting_ = CuttingTorque::kRgd;
};

}  // namespace drillwave::bitrock
