#include "drillwave/bitrock/rgd.hpp"

#include <algorithm>
#include <cstdint>

#include <boost/math/tools/toms748_solve.hpp>

#include "drillwave/core/constants.hpp"

namespace drillwave::bitrock {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

void RgdLaw::OnBottom(Turn turn, Axial axial, double w, bool cutting, double z, RgdForces& f) const {
  const double d = std::max(f.depth, 0.0);
  const double strength = strength_heterogeneity.Multiplier(z);  // exactly 1 for homogeneous rock
  f.cut_weight = cutting ? CutWeightPerDepth() * d * strength : 0.0;
  // A stuck bit twisted backward cannot be lifted by its own cutters: lifted, its wear flats would hold nothing, it
  // would turn back and stop cutting, and the lift would be gone (no regime is consistent; the run chattered between
  // four every 4e-11 s, after a long stick left a depth of cut whose cutting weight was twice the weight on bit). At
  // rest its cutters answer the weight pressing them, up to the cutting weight, and no more. (Twisted forward, stuck
  // and lifted is consistent: the cutters keep cutting when it turns; the independent simulator's bouncing bit lifts
  // so.)
  const bool reaction = turn == Turn::kStuck && f.drive_torque < 0 && f.cut_weight > std::max(f.drive_force, 0.0);
  if (reaction) f.cut_weight = std::max(f.drive_force, 0.0);
  // Held with its cutters a reaction, the bit is on the edge of lifting (net force 0) but lifts only when pulled up.
  f.lift_margin = reaction ? f.drive_force : f.drive_force - f.cut_weight;
  const double cut_torque = cutting ? CutTorquePerDepth() * d * strength : 0.0;
  const double contact_force = ContactForce() * strength;
  double contact = 0;  // W_f
  switch (axial) {
    case Axial::kAdvancing: contact = contact_force; break;
    case Axial::kLifting: contact = 0; break;
    case Axial::kHeld: contact = std::clamp(f.drive_force - f.cut_weight, 0.0, contact_force); break;
  }
  f.weight = f.cut_weight + contact;
  const double friction = FrictionArm(w) * contact, holding = StaticFrictionArm() * contact;
  f.torque = turn == Turn::kBackward ? -friction : contact_law.CutTorque(cut_torque, w) + friction;
  f.static_forward = contact_law.CutTorqueAtRest(cut_torque) + holding;
  // A bit that starts to turn backward stops cutting, and a held bit's wear flats then take the cutters' share of
  // the weight too: the backward slip threshold is the holding of that contact (with the held contact, net less the
  // cut weight, a bit whose torque lies between the two would slip back only to be held again).
  const double contact_turning_back = axial == Axial::kHeld ? std::clamp(f.drive_force, 0.0, contact_force) : contact;
  f.static_backward = StaticFrictionArm() * contact_turning_back;
}

CutProfile::CutProfile(int blades, double omega0, double rop0, int surface_passes, const BottomRoughness& roughness)
    : blades_(blades),
      surface_passes_(surface_passes),
      omega0_(omega0),
      history_(2, [omega0, rop0, roughness](double t, double* v, double* d) {
        // Steady drilling before t = 0, where the blades passed at angle omega0 t over the rough bottom.
        v[0] = omega0 * t, v[1] = rop0 * t;
        d[0] = omega0, d[1] = rop0;
        if (roughness.on()) v[1] += roughness.Depth(omega0 * t), d[1] += omega0 * roughness.Slope(omega0 * t);
      }) {}

// When the bit angle last stood `back` radians behind phi, from the stored angle. The root lies near t - guess (t_n
// changes little from one evaluation to the next): Newton from there takes two or three look-ups; where it cannot (the
// bit stood still or turned back there), a bracket around it, widened if needed, and TOMS 748 inside it.
double CutProfile::TimeAngleBehind(double phi, double t, integration::Side side, double back, double guess) const {
  const double target = phi - back;
  const double width = 1e-12 * (1 + std::abs(t));
  // Newton from the guess (the last committed t_n: a step earlier, so usually two or three iterations), while the
  // bit turned forward where it looks; the bracketing search below when it did not or Newton wanders.
  double s = t - guess;
  for (int i = 0; i < 6 && s < t && s > t - 4 * guess; ++i) {
    double angle[2], rate[2];
    history_.ValuesAndDerivatives(s, angle, rate, side);
    if (!(rate[0] > 0)) break;
    const double step = (angle[0] - target) / rate[0];
    s -= step;
    if (std::abs(step) <= width && s < t) return s;
  }
  auto behind = [&](double time) { return (time >= t ? phi : history_.Value(time, 0, side)) - target; };
  double lo = t - guess, hi = t;
  double g_lo = behind(lo), g_hi = back;
  for (int i = 0; i < 60 && g_lo > 0; ++i) hi = lo, g_hi = g_lo, lo = t - (t - lo) * 2, g_lo = behind(lo);
  if (g_lo >= 0) return lo;  // on the root, or the history holds no such angle (then the oldest time looked at)
  std::uintmax_t iterations = 60;
  const auto [a, b] = boost::math::tools::toms748_solve(
      behind, lo, hi, g_lo, g_hi, [width](double l, double h) { return h - l <= width; }, iterations);
  return 0.5 * (a + b);
}

double CutProfile::DepthOfCut(double phi, double u, double t, integration::Side side, bool contact,
                              double last_contact_change, double* tn) const {
  const double pitch = 2 * kPi / blades_;
  double guess = tn_committed_ > 0 ? tn_committed_ : pitch / std::max(omega0_, 1e-3);
  double surface = -kInf;
  for (int k = 1; k <= surface_passes_; ++k) {
    const double s = TimeAngleBehind(phi, t, side, k * pitch, k * guess);
    if (k == 1) guess = t - s;
    if (k == 1 && tn) *tn = t - s;
    surface = std::max(surface, s >= t ? u : history_.Value(s, 1, side));
    // In contact ever since the previous blade passed (no lift-off or landing, no backward turn since then): that
    // blade is the deepest.
    if (k == 1 && contact && last_contact_change < s && phi_max_ <= phi) break;
  }
  return blades_ * (u - surface);
}

void CutProfile::Commit(const integration::Piece& p, int phi_index, int u_index, bool contact,
                        double last_contact_change, double keep) {
  const double b0[2] = {p.x0[phi_index], p.x0[u_index]}, b1[2] = {p.x1[phi_index], p.x1[u_index]};
  const double bm[2] = {p.x_mid[phi_index], p.x_mid[u_index]};
  const double e0[2] = {p.f0[phi_index], p.f0[u_index]}, e1[2] = {p.f1[phi_index], p.f1[u_index]};
  history_.Append(p.t0, b0, e0, p.t1, b1, e1, bm);
  phi_max_before_ = std::max(phi_max_before_, p.x0[phi_index]);
  phi_max_ = std::max({phi_max_, p.x0[phi_index], p.x1[phi_index]});
  last_end_ = p.t1;
  DepthOfCut(p.x1[phi_index], p.x1[u_index], p.t1, integration::Side::kLeft, contact, last_contact_change,
             &tn_committed_);
  history_.DiscardBefore(p.t1 - std::max(keep, 20.0 * tn_committed_ + 5.0));
}

}  // namespace drillwave::bitrock
