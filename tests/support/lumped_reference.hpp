#pragma once
// An independent reference for the torsional drill string, with no waves and no delays: the string cut into N
// equal elements, each a torsional spring k = G J N / L whose inertia rho J L / N is split to its two end nodes.
//   node 0 (top):  half an element's inertia, dissipative top torque beta (Omega(t) - v_0)
//   nodes 1..N-1:  one element's inertia
//   node N (bit):  I_B + half an element's inertia, bit friction (set-valued laws: stuck/slip regimes with events)
// As N grows this finite-element (lumped-mass) ODE converges to the wave equation the engine solves exactly by
// d'Alembert; the semi-discretization error is O(1/N^2) for smooth solutions. It shares only the generic event
// and stepping loop (integration::Simulator) with the engine, none of the wave network.
//
// Header-only, so that tests and apps/bench can use it without extra sources.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "drillwave/cases/friction_json.hpp"
#include "drillwave/bitrock/friction.hpp"
#include "drillwave/integration/simulator.hpp"
#include "drillwave/model/schedule.hpp"

namespace drillwave::lumped_reference {

struct LumpedStringParams {
  double length_m = 1172;              // L
  double shear_modulus_pa = 79.3e9;    // G
  double density_kg_m3 = 8000;         // rho
  double polar_moment_m4 = 1.19e-5;    // J
  double beta = 2000;                  // dissipative top [N·m·s/rad]
  double bit_inertia = 89;             // I_B [kg·m^2]
  model::Schedule top_speed = model::Schedule({{0.0, 0.0}, {2.0, 10.0}});  // Omega(t) [rad/s]
  bitrock::FrictionLaw friction = bitrock::FrictionLaw(bitrock::Stribeck{97347, 0.155575, 0.5, 0.8, 0.9, 1.0, 0.03});

  // The parameters of a "torsional_wave" case document with one section, a dissipative top and a bit with inertia
  // (e.g. json-cases/saldivar-stickslip.json). Throws std::invalid_argument for anything else.
  static LumpedStringParams FromCase(const nlohmann::json& doc);
};

struct StatisticsWindow {
  double begin_s = 40, end_s = 80;
};

// Same definitions as cases::ComputeStickSlipStatistics: period = mean interval between successive stick onsets
// inside the window (NaN if fewer than two), stick fraction = stuck time in the window / window length, mean speed
// from the bit angle at the window ends, max speed over the window.
struct LumpedStringResult {
  double stick_slip_period_s = std::numeric_limits<double>::quiet_NaN();
  double stick_fraction = 0;
  double bit_speed_max = 0;
  double bit_speed_mean = 0;
  int stick_onsets = 0;  // in the window
  long steps = 0, evaluations = 0, events = 0;
  double wall_time_s = 0;  // integration only
};

// The lumped string as a Process for integration::Simulator.
// State: node speeds v_0..v_N, element twists theta_e = phi_{e-1} - phi_e (e = 1..N), bit angle. Twists rather than
// angles keep the spring torques free of cancellation between two large angles.
class LumpedStringProcess {
 public:
  using State = std::vector<double>;
  enum Regime { kSlipNegative = -1, kStuck = 0, kSlipPositive = 1 };

  LumpedStringProcess(const LumpedStringParams& p, int n_elements, double t0)
      : p_(p), n_(n_elements), last_breakpoint_(t0) {
    if (n_elements < 1) throw std::invalid_argument("lumped reference: n_elements must be >= 1");
    const double element_inertia = p.density_kg_m3 * p.polar_moment_m4 * p.length_m / n_;
    inverse_inertia_.assign(n_ + 1, 1.0 / element_inertia);
    inverse_inertia_[0] = 1.0 / (0.5 * element_inertia);
    inverse_inertia_[n_] = 1.0 / (0.5 * element_inertia + p.bit_inertia);
    stiffness_ = p.shear_modulus_pa * p.polar_moment_m4 * n_ / p.length_m;
    static_positive_ = p.friction.StaticPositive();
    static_negative_ = p.friction.StaticNegative();
    set_valued_ = p.friction.IsSetValued();
  }

  int Dimension() const { return 2 * n_ + 2; }
  int BitSpeedIndex() const { return n_; }
  int BitAngleIndex() const { return 2 * n_ + 1; }

  // At rest: a set-valued bit starts stuck if the driving torque (none) is within its static range.
  State InitialState() {
    regime_ = set_valued_ ? kStuck : kSlipPositive;
    return State(Dimension(), 0.0);
  }

  // An ODE: no delays, no history.
  double MaxStep() const { return std::numeric_limits<double>::infinity(); }
  void BeginStep(double) {}
  double PrepareCommit(const integration::Piece&, double, double) { return 0; }
  void Commit(const integration::Piece&) {}

  void Derivatives(const State& x, State& dx, double t) const {
    const double* v = x.data();
    const double* theta = x.data() + n_;  // theta[e], e = 1..N
    const bool stuck = set_valued_ && regime_ == kStuck;
    // Top node.
    double torque_above = stiffness_ * theta[1];  // torque carried by element 1
    dx[0] = (p_.beta * (p_.top_speed.Value(t) - v[0]) - torque_above) * inverse_inertia_[0];
    // Interior nodes.
    for (int j = 1; j < n_; ++j) {
      const double torque_below = stiffness_ * theta[j + 1];
      dx[j] = (torque_above - torque_below) * inverse_inertia_[j];
      torque_above = torque_below;
    }
    // Bit: torque_above is now the torque of element N.
    const double v_bit = stuck ? 0.0 : v[n_];
    dx[n_] = stuck ? 0.0 : (torque_above - Friction(v_bit)) * inverse_inertia_[n_];
    for (int e = 1; e < n_; ++e) dx[n_ + e] = v[e - 1] - v[e];
    dx[2 * n_] = v[n_ - 1] - v_bit;
    dx[2 * n_ + 1] = v_bit;
  }

  int NumWitnesses() const { return 2; }
  // Slipping: witness 0 is the speed in the slip direction (the bit stops). Stuck: the margins of the driving torque
  // to the two static limits (the bit breaks free). Smooth friction: no events.
  double Witness(int i, double, const State& x) const {
    if (!set_valued_) return 1.0;
    if (regime_ == kStuck) {
      const double drive = DrivingTorqueOnBit(x);
      return i == 0 ? static_positive_ - drive : drive + static_negative_;
    }
    return i == 0 ? regime_ * x[n_] : 1.0;
  }

  bool OnEvent(int i, double t, State& x) {
    const Regime before = regime_;
    if (regime_ == kStuck) {
      regime_ = i == 0 ? kSlipPositive : kSlipNegative;
    } else {  // the bit has come to rest: it stays if friction can hold the driving torque, else it turns back
      const double drive = DrivingTorqueOnBit(x);
      regime_ = drive > static_positive_ ? kSlipPositive : (drive < -static_negative_ ? kSlipNegative : kStuck);
    }
    if (regime_ == kStuck || before == kStuck) x[n_] = 0;
    if (regime_ == kStuck && before != kStuck) stick_onsets_.push_back(t);
    if (regime_ != kStuck && before == kStuck) releases_.push_back(t);
    return regime_ != before;
  }

  // The knots of the top speed schedule (kinks or jumps of Omega).
  double NextBreakpoint() const {
    for (const auto& k : p_.top_speed.knots())
      if (k.first > last_breakpoint_) return k.first;
    return std::numeric_limits<double>::infinity();
  }
  void OnBreakpoint(double t) { last_breakpoint_ = t; }

  // Torque the string exerts on the bit held at rest: what static friction must balance.
  double DrivingTorqueOnBit(const State& x) const { return stiffness_ * x[2 * n_]; }
  Regime regime() const { return regime_; }
  const std::vector<double>& stick_onsets() const { return stick_onsets_; }
  const std::vector<double>& releases() const { return releases_; }

 private:
  double Friction(double v) const {
    if (!set_valued_) return p_.friction.SlipTorque(v);
    // Trial stages may overshoot a stop before its event is located: continue the slip branch by its limit at 0.
    constexpr double kTiny = 1e-300;
    return regime_ == kSlipPositive ? p_.friction.SlipTorque(std::max(v, kTiny))
                                    : p_.friction.SlipTorque(std::min(v, -kTiny));
  }

  const LumpedStringParams& p_;
  int n_;
  std::vector<double> inverse_inertia_;
  double stiffness_;
  double static_positive_ = 0, static_negative_ = 0;
  bool set_valued_ = false;
  Regime regime_ = kStuck;
  double last_breakpoint_;
  std::vector<double> stick_onsets_, releases_;
};

namespace detail {
// Component i of the piece's quartic at t (integration::InterpolatePiece for one component).
inline double PieceComponent(const integration::Piece& p, std::size_t i, double t) {
  const double h = p.t1 - p.t0, s = (t - p.t0) / h, s2 = s * s, s3 = s2 * s, r = 1 - s;
  const double cubic_mid = 0.5 * (p.x0[i] + p.x1[i]) + 0.125 * h * (p.f0[i] - p.f1[i]);
  return (2 * s3 - 3 * s2 + 1) * p.x0[i] + (s3 - 2 * s2 + s) * h * p.f0[i] + (-2 * s3 + 3 * s2) * p.x1[i] +
         (s3 - s2) * h * p.f1[i] + 16.0 * (p.x_mid[i] - cubic_mid) * s2 * r * r;
}
}  // namespace detail

// Simulates the lumped string from rest at t = 0 to t_end and returns the stick-slip statistics over the window.
// options.control_history_error is switched off: the reference keeps no history, so nothing reads its interpolant
// between steps (events are located on the stepper's own dense output).
inline LumpedStringResult SimulateLumpedString(const LumpedStringParams& p, int n_elements, double t_end,
                                               StatisticsWindow window, integration::IntegratorOptions options) {
  if (!(window.begin_s < window.end_s) || window.end_s > t_end)
    throw std::invalid_argument("lumped reference: the window must satisfy begin < end <= t_end");
  options.control_history_error = false;
  LumpedStringProcess process(p, n_elements, 0.0);
  integration::Simulator<LumpedStringProcess> simulator(process, options);
  const std::size_t bit_speed = process.BitSpeedIndex(), bit_angle = process.BitAngleIndex();

  // The bit angle at the window ends, from the first piece reaching each (clamped to the piece: pieces that end on a
  // breakpoint may leave a gap of rounding size before the next one).
  double angle_begin = 0, angle_end = 0;
  bool have_begin = false, have_end = false;
  auto angle_at = [&](const integration::Piece& piece, double t) {
    return detail::PieceComponent(piece, bit_angle, std::clamp(t, piece.t0, piece.t1));
  };
  double speed_max = -std::numeric_limits<double>::infinity();
  auto observer = [&](const integration::Piece& piece) {
    if (!have_begin && piece.t1 >= window.begin_s) {
      angle_begin = angle_at(piece, window.begin_s);
      have_begin = true;
    }
    if (!have_end && piece.t1 >= window.end_s) {
      angle_end = angle_at(piece, window.end_s);
      have_end = true;
    }
    if (piece.t1 < window.begin_s || piece.t0 > window.end_s) return;
    // The bit speed at the piece's ends and three interior points (a maximum inside a step is found to within the
    // quartic's resolution, which is ample for a statistic).
    for (double s : {0.0, 0.25, 0.5, 0.75, 1.0}) {
      const double t = piece.t0 + s * (piece.t1 - piece.t0);
      if (t < window.begin_s || t > window.end_s) continue;
      speed_max = std::max(speed_max, detail::PieceComponent(piece, bit_speed, t));
    }
  };
  const std::vector<double> x_end = simulator.Integrate(0.0, process.InitialState(), t_end, observer);
  if (!have_end) angle_end = x_end[bit_angle];  // the window ends at t_end and the last piece stopped just short

  LumpedStringResult r;
  const auto& onsets = process.stick_onsets();
  const auto& releases = process.releases();
  std::vector<double> in_window;
  double stuck_time = 0;
  // Stuck intervals: the initial one (from 0) and one per onset, each ended by the next release (or never).
  std::vector<std::pair<double, double>> stuck;
  std::size_t next_release = 0;
  auto release_after = [&](double t) {
    while (next_release < releases.size() && releases[next_release] < t) ++next_release;
    return next_release < releases.size() ? releases[next_release] : std::numeric_limits<double>::infinity();
  };
  if (p.friction.IsSetValued()) stuck.push_back({0.0, release_after(0.0)});
  for (double t : onsets) stuck.push_back({t, release_after(t)});
  for (const auto& [a, b] : stuck) {
    if (a >= window.begin_s && a < window.end_s) in_window.push_back(a);
    const double lo = std::max(a, window.begin_s), hi = std::min(b, window.end_s);
    if (hi > lo) stuck_time += hi - lo;
  }
  const double length = window.end_s - window.begin_s;
  r.stick_onsets = static_cast<int>(in_window.size());
  if (in_window.size() >= 2) r.stick_slip_period_s = (in_window.back() - in_window.front()) / (in_window.size() - 1);
  r.stick_fraction = stuck_time / length;
  r.bit_speed_max = speed_max;
  r.bit_speed_mean = (angle_end - angle_begin) / length;
  const auto& stats = simulator.stats();
  r.steps = stats.steps;
  r.evaluations = stats.derivative_evaluations;
  r.events = stats.events;
  r.wall_time_s = stats.wall_time_s;
  return r;
}

inline LumpedStringParams LumpedStringParams::FromCase(const nlohmann::json& doc) {
  auto fail = [](const std::string& what) {
    throw std::invalid_argument("lumped reference: the case must be a torsional_wave with " + what);
  };
  const auto& m = doc.at("model");
  if (m.at("kind") != "torsional_wave") fail("model.kind = torsional_wave");
  const auto& sections = m.at("string").at("sections");
  if (sections.size() != 1) fail("exactly one section");
  if (m.at("string").value("torsional_damping_Nms_per_rad_m", 0.0) != 0) fail("no distributed damping");
  const auto& s = sections.at(0);
  if (!s.contains("polar_moment_m4")) fail("the section's polar_moment_m4");
  const auto& top = m.at("top");
  if (top.at("type") != "dissipative" || top.value("damping_Nms_per_rad", 0.0) != 0) fail("a dissipative top");
  const auto& bit = m.at("bit");
  if (bit.value("damping_Nms_per_rad", 0.0) != 0 || !bit.contains("friction")) fail("a bit with friction, no damper");
  if (m.contains("initial") && m["initial"].value("bit_speed_rad_s", 0.0) != 0) fail("a string at rest at t = 0");
  LumpedStringParams p;
  p.length_m = s.at("length_m").get<double>();
  p.shear_modulus_pa = s.at("shear_modulus_Pa").get<double>();
  p.density_kg_m3 = s.at("density_kg_m3").get<double>();
  p.polar_moment_m4 = s.at("polar_moment_m4").get<double>();
  p.beta = top.at("beta_Nms_per_rad").get<double>();
  p.top_speed = model::Schedule::FromJson(top.at("speed_rad_s"), "/model/top/speed_rad_s");
  p.bit_inertia = bit.at("inertia_kgm2").get<double>();
  p.friction = cases::ReadFrictionLaw(bit.at("friction"), "/model/bit/friction");
  return p;
}

}  // namespace drillwave::lumped_reference
