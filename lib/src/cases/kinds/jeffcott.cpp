// Model kind "jeffcott": the lateral-torsional Jeffcott rotor of the failure seed (eqs. 1-23). A rotor of mass M
// and inertia I_0 at mid-span of a shaft fixed at both ends, an unbalance mass m_b at eccentricity e; the drive
// turns the shaft's end at a prescribed angle theta(t) and the rotor lags it by the twist gamma, so the rotor's
// angle is beta = theta + gamma (eq. 1). With m = M + m_b, a = m_b e, I = I_0 + m_b e^2 (eqs. 21-23, with the
// drive's acceleration kept, which the seed drops for a constant speed):
//   m x'' + c_b x' + k_b x = a (beta'' sin beta + beta'^2 cos beta)
//   m y'' + c_b y' + k_b y = a (beta'^2 sin beta - beta'' cos beta)
//   I gamma'' + c_tor gamma' + k_tor gamma = a (x'' sin beta - y'' cos beta) - I theta'' + T(t)
// a mass-matrix system solved for (x'', y'', gamma'') at every evaluation. k_b = 192 E I_a / L^3 (eq. 16, fixed
// ends), k_tor = G J / L (eq. 17), c_b = 2 zeta_b w_b m, c_tor = 2 zeta_tor w_tor I with w_b = sqrt(k_b / m),
// w_tor = sqrt(k_tor / I) (eq. 19).
#include <cmath>
#include <limits>

#include "drillwave/analysis/fatigue.hpp"
#include "drillwave/cases/kinds.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/integration/simulator.hpp"
#include "drillwave/model/schedule.hpp"

namespace drillwave::cases {
namespace {

using io::JsonReader;
using Range = io::Range;

struct Rotor {
  double rotor_mass = 1, rotor_inertia = 1, unbalance_mass = 0, eccentricity = 0;
  double bending_stiffness = 1, torsional_stiffness = 1;
  double bending_damping_ratio = 0, torsional_damping_ratio = 0;
  model::Schedule drive_speed;  // theta'(t) [rad/s]
  model::Schedule torque;       // T(t) on the rotor [N·m]; negative: a reverse (braking) torque
  // Stress at the shaft's outer surface per unit deflection and per unit twist; known when the shaft is given by
  // its geometry (0 otherwise: no stress summary).
  double bending_stress_per_m = 0, shear_stress_per_rad = 0;
  analysis::SnCurve sn_curve = analysis::SnCurve::MildSteel();

  double mass() const { return rotor_mass + unbalance_mass; }
  double inertia() const { return rotor_inertia + unbalance_mass * eccentricity * eccentricity; }
  double bending_frequency() const { return std::sqrt(bending_stiffness / mass()); }        // w_b [rad/s]
  double torsional_frequency() const { return std::sqrt(torsional_stiffness / inertia()); }  // w_tor [rad/s]
  double bending_damping() const { return 2 * bending_damping_ratio * bending_frequency() * mass(); }
  double torsional_damping() const { return 2 * torsional_damping_ratio * torsional_frequency() * inertia(); }
};

// State: x, y, gamma, x', y', gamma', theta.
class RotorProcess : public integration::WithoutHistory {
 public:
  using State = std::vector<double>;
  explicit RotorProcess(const Rotor& r) : r_(r), c_b_(r.bending_damping()), c_tor_(r.torsional_damping()) {}

  int Dimension() const { return 7; }
  void BeginStep(double t0) { step_start_ = t0; }
  int NumWitnesses() const { return 0; }
  double Witness(int, double, const State&) const { return 1; }
  bool OnEvent(int, double, State&) { return false; }
  double NextBreakpoint() const {
    return std::min(r_.drive_speed.NextKnotAfter(passed_), r_.torque.NextKnotAfter(passed_));
  }
  void OnBreakpoint(double t) { passed_ = t; }

  void Derivatives(const State& s, State& ds, double t) const {
    double xdd, ydd, gdd;
    Accelerations(s, t, xdd, ydd, gdd);
    ds[0] = s[3], ds[1] = s[4], ds[2] = s[5];
    ds[3] = xdd, ds[4] = ydd, ds[5] = gdd;
    ds[6] = Drive(t).first;
  }

  // Solves the symmetric positive definite 3 x 3 mass-matrix system for (x'', y'', gamma'').
  void Accelerations(const State& s, double t, double& xdd, double& ydd, double& gdd) const {
    const auto [omega, omega_dot] = Drive(t);
    const double beta = s[6] + s[2], beta_dot = omega + s[5];
    const double sn = std::sin(beta), cs = std::cos(beta);
    const double m = r_.mass(), a = r_.unbalance_mass * r_.eccentricity, inertia = r_.inertia();
    const double torque = r_.torque.Evaluate(t, t > step_start_).first;
    // [m 0 -a sn; 0 m a cs; -a sn a cs I] (x'', y'', gamma'') = f
    const double f1 = a * sn * omega_dot + a * beta_dot * beta_dot * cs - c_b_ * s[3] - r_.bending_stiffness * s[0];
    const double f2 = a * beta_dot * beta_dot * sn - a * cs * omega_dot - c_b_ * s[4] - r_.bending_stiffness * s[1];
    const double f3 = torque - inertia * omega_dot - c_tor_ * s[5] - r_.torsional_stiffness * s[2];
    // Eliminate x'' and y'' from the third row: (I - a^2 / m) gamma'' = f3 + (a / m)(sn f1 - cs f2).
    gdd = (f3 + (a / m) * (sn * f1 - cs * f2)) / (inertia - a * a / m);
    xdd = (f1 + a * sn * gdd) / m;
    ydd = (f2 - a * cs * gdd) / m;
  }

  std::pair<double, double> Drive(double t) const { return r_.drive_speed.Evaluate(t, t > step_start_); }
  double BendingDamping() const { return c_b_; }
  double TorsionalDamping() const { return c_tor_; }

 private:
  const Rotor& r_;
  double c_b_, c_tor_;
  double step_start_ = 0, passed_ = 0;
};

// theta'(t) from drive_speed_rad_s, or from drive_speed_ratio times w_b (the seed's frequency ratio eta, so that a
// sweep over the unbalance mass keeps the rotor at the same fraction of its own critical speed).
model::Schedule DriveSpeed(const JsonReader& r, double bending_frequency) {
  if (r.Has("drive_speed_ratio") == r.Has("drive_speed_rad_s"))
    throw InputError(r.PathOf("drive_speed_rad_s"), "expected exactly one of drive_speed_rad_s and drive_speed_ratio");
  if (r.Has("drive_speed_rad_s"))
    return model::Schedule::FromJson(r.Raw("drive_speed_rad_s"), r.PathOf("drive_speed_rad_s"));
  auto knots = model::Schedule::FromJson(r.Raw("drive_speed_ratio"), r.PathOf("drive_speed_ratio")).knots();
  for (auto& knot : knots) knot.second *= bending_frequency;
  return model::Schedule(std::move(knots));
}

// The drive speed rotor_speed_norm divides the rotor's by while the drive is at rest (the seed's beta'/theta' is
// undefined there): the speed of the drive's last turning knot up to t, i.e. the speed it ran at before it stopped;
// before it has turned, the speed of its first turning knot; for a drive that never turns, the bending natural
// frequency w_b (the seed's scale of drive speeds). Never 0, so a drive coming to rest leaves the channel defined.
double SpeedAtRest(const model::Schedule& drive, double t, double bending_frequency) {
  double last = 0, first = 0;
  for (const auto& [time, value] : drive.knots()) {
    if (value == 0 || !std::isfinite(value)) continue;
    if (first == 0) first = value;
    if (time <= t) last = value;
  }
  return last != 0 ? last : first != 0 ? first : bending_frequency;
}

// The time after which the deflection stays within 2 % of its mean over the window (0 if it always does).
double SettlingTime(const std::vector<double>& time, const std::vector<double>& deflection, double window_mean) {
  for (std::size_t i = time.size(); i-- > 0;)
    if (std::abs(deflection[i] - window_mean) > 0.02 * window_mean) return i + 1 < time.size() ? time[i + 1] : time[i];
  return 0;
}

// The window's samples of the motion that stress the shaft.
struct Motion {
  std::vector<double> x, y, rotor_angle, twist;
};

// Stresses and fatigue over the window. Bending: sigma_b = M c / I at the fixed ends and midspan, where the central
// load P = k_b * deflection bends a fixed-fixed shaft by M = P L / 8; a fibre at angle psi on the rotor sees the
// deflection's component along its own direction (beta + psi), so synchronous whirl bends each fibre steadily and
// only changes of the whirl load it in cycles. Torsion: tau = T c / J with T = k_tor gamma. Von Mises combines the
// two at the worst fibre. Damage: Miner over the rainflow cycles of the worst of kFibres fibres' bending stress,
// plus that of sqrt(3) tau (the von Mises equivalent of pure shear) on the same S-N curve.
nlohmann::json StressSummary(const Rotor& r, const Motion& m) {
  constexpr int kFibres = 24;
  double deflection_max = 0, twist_max = 0, von_mises_max = 0;
  std::vector<double> equivalent_shear;
  for (std::size_t i = 0; i < m.x.size(); ++i) {
    const double sigma = r.bending_stress_per_m * std::hypot(m.x[i], m.y[i]);
    const double tau = r.shear_stress_per_rad * m.twist[i];
    deflection_max = std::max(deflection_max, std::hypot(m.x[i], m.y[i]));
    twist_max = std::max(twist_max, std::abs(m.twist[i]));
    von_mises_max = std::max(von_mises_max, std::sqrt(sigma * sigma + 3 * tau * tau));
    equivalent_shear.push_back(std::sqrt(3.0) * tau);
  }
  double bending_damage = 0;
  std::vector<double> fibre(m.x.size());
  for (int k = 0; k < kFibres; ++k) {
    const double psi = 2 * kPi * k / kFibres;
    for (std::size_t i = 0; i < m.x.size(); ++i)
      fibre[i] = r.bending_stress_per_m *
                 (m.x[i] * std::cos(m.rotor_angle[i] + psi) + m.y[i] * std::sin(m.rotor_angle[i] + psi));
    bending_damage = std::max(bending_damage, analysis::MinerDamage(analysis::RainflowCount(fibre), r.sn_curve));
  }
  const double torsion_damage = analysis::MinerDamage(analysis::RainflowCount(equivalent_shear), r.sn_curve);
  return {{"max_bending_stress_Pa", r.bending_stress_per_m * deflection_max},
          {"max_shear_stress_Pa", r.shear_stress_per_rad * twist_max},
          {"max_von_mises_stress_Pa", von_mises_max},
          {"fatigue_damage_bending_miner", bending_damage},
          {"fatigue_damage_torsion_miner", torsion_damage},
          {"fatigue_damage_miner", bending_damage + torsion_damage}};
}

class JeffcottModel : public PreparedModel {
 public:
  explicit JeffcottModel(Rotor r) : r_(std::move(r)) {}

  RunResult Run(const RunSettings& settings) const override {
    RotorProcess process(r_);
    std::vector<double> x(7, 0.0);
    std::vector<double> time, xs, ys, radius, twist, drive, rotor, shaft_torque, torque, normalized, rotor_angle;
    auto sample = [&](double t, const std::vector<double>& s) {
      const double omega = process.Drive(t).first, beta_dot = omega + s[5];
      time.push_back(t), xs.push_back(s[0]), ys.push_back(s[1]), radius.push_back(std::hypot(s[0], s[1]));
      twist.push_back(s[2]), drive.push_back(omega), rotor.push_back(beta_dot), rotor_angle.push_back(s[6] + s[2]);
      shaft_torque.push_back(r_.torsional_stiffness * s[2] + process.TorsionalDamping() * s[5]);
      torque.push_back(r_.torque.Value(t));
      // beta'/theta' (the seed's normalized speed); 1 while both rest; relative to SpeedAtRest while only the drive
      // rests (a drive that comes to rest leaves the rotor turning and swinging on the shaft).
      const double ratio = omega != 0 ? beta_dot / omega : beta_dot == 0 ? 1.0 : std::nan("");
      normalized.push_back(std::isfinite(ratio) ? ratio
                                                : beta_dot / SpeedAtRest(r_.drive_speed, t, r_.bending_frequency()));
    };
    sample(0.0, x);
    const auto observer = integration::SampleEvery(settings.output_interval_s, sample);
    integration::Simulator<RotorProcess> sim(process, settings.integrator);
    sim.Integrate(0.0, x, settings.duration_s, observer);

    RunResult result;
    // Statistics over the window.
    double r_max = 0, r_min = std::numeric_limits<double>::infinity(), r_sum = 0, g_max = -1e300, g_min = 1e300;
    double w_min = 1e300, w_max = -1e300, w_sum = 0, drive_sum = 0, g_sum = 0;
    int n = 0;
    Motion window;
    for (std::size_t i = 0; i < time.size(); ++i) {
      if (time[i] < settings.window_begin_s || time[i] > settings.window_end_s) continue;
      window.x.push_back(xs[i]), window.y.push_back(ys[i]), window.twist.push_back(twist[i]);
      window.rotor_angle.push_back(rotor_angle[i]);
      r_max = std::max(r_max, radius[i]), r_min = std::min(r_min, radius[i]), r_sum += radius[i];
      g_max = std::max(g_max, twist[i]), g_min = std::min(g_min, twist[i]), g_sum += twist[i];
      w_max = std::max(w_max, rotor[i]), w_min = std::min(w_min, rotor[i]), w_sum += rotor[i];
      drive_sum += drive[i];
      ++n;
    }
    const double w_b = r_.bending_frequency();
    result.summary = {{"deflection_max_m", n ? r_max : 0.0},
                      {"deflection_min_m", n ? r_min : 0.0},
                      {"deflection_mean_m", n ? r_sum / n : 0.0},
                      {"deflection_settling_time_s", n ? SettlingTime(time, radius, r_sum / n) : 0.0},
                      {"twist_max_rad", n ? g_max : 0.0},
                      {"twist_min_rad", n ? g_min : 0.0},
                      {"twist_mean_rad", n ? g_sum / n : 0.0},
                      {"rotor_speed_max_rad_s", n ? w_max : 0.0},
                      {"rotor_speed_min_rad_s", n ? w_min : 0.0},
                      {"rotor_speed_mean_rad_s", n ? w_sum / n : 0.0},
                      {"frequency_ratio", n ? (drive_sum / n) / w_b : 0.0},
                      {"bending_natural_frequency_rad_s", w_b},
                      {"critical_speed_rpm", w_b * 30 / kPi},
                      {"torsional_natural_frequency_rad_s", r_.torsional_frequency()},
                      {"bending_damping_Ns_per_m", process.BendingDamping()},
                      {"torsional_damping_Nms_per_rad", process.TorsionalDamping()},
                      {"steps", sim.stats().steps},
                      {"events", sim.stats().events},
                      {"derivative_evaluations", sim.stats().derivative_evaluations}};
    if (r_.bending_stress_per_m > 0) result.summary.update(StressSummary(r_, window));
    result.channels = {{"top_rpm", ToRpm(drive)},        {"bit_rpm", ToRpm(rotor)},
                       {"top_torque_Nm", shaft_torque},  {"bit_torque_Nm", torque},
                       {"x_m", std::move(xs)},           {"y_m", std::move(ys)},
                       {"deflection_m", std::move(radius)}, {"twist_rad", std::move(twist)},
                       {"rotor_speed_norm", std::move(normalized)}};
    result.plot_panels = {{"deflection_m", "x_m", "y_m"}, {"twist_rad"}, {"top_rpm", "bit_rpm"}};
    result.time_s = std::move(time);
    return result;
  }

 private:
  Rotor r_;
};

class JeffcottKind : public ModelKind {
 public:
  std::string name() const override { return "jeffcott"; }
  std::string description() const override {
    return "lateral-torsional Jeffcott rotor with unbalance (failure seed eqs. 1-23): lateral x, y and twist gamma "
           "of a rotor on a shaft fixed at both ends, driven at a prescribed speed";
  }
  nlohmann::json FieldSchema() const override {
    return {{"rotor_mass_kg", "M > 0"},
            {"rotor_inertia_kgm2", "I_0 > 0"},
            {"unbalance_mass_kg", "m_b >= 0"},
            {"eccentricity_m", "e >= 0"},
            {"shaft/bending_stiffness_N_per_m", "k_b > 0, or from the geometry below"},
            {"shaft/torsional_stiffness_Nm_per_rad", "k_tor > 0, or from the geometry below"},
            {"shaft/outer_diameter_m", "> 0 (with inner_diameter_m, length_m, youngs_modulus_Pa, shear_modulus_Pa: "
                                       "k_b = 192 E I / L^3, eq. 16; k_tor = G J / L, eq. 17)"},
            {"shaft/inner_diameter_m", ">= 0, < outer"},
            {"shaft/length_m", "> 0, between the fixed ends"},
            {"shaft/youngs_modulus_Pa", "> 0"},
            {"shaft/shear_modulus_Pa", "> 0"},
            {"bending_damping_ratio", "zeta_b >= 0: c_b = 2 zeta_b w_b (M + m_b), eq. 19"},
            {"torsional_damping_ratio", "zeta_tor >= 0: c_tor = 2 zeta_tor w_tor (I_0 + m_b e^2), eq. 19"},
            {"drive_speed_rad_s", "theta'(t): a number or {\"knots\": [[t, v], ...]} [rad/s]"},
            {"drive_speed_ratio", "instead of drive_speed_rad_s: theta'(t) / w_b, the seed's frequency ratio eta, "
                                  "a number or knots"},
            {"torque_Nm", "external torque on the rotor, schedule, default 0 (negative: reverse / brake torque)"},
            {"fatigue/sn_coefficient_Pa",
             "a > 0 of the S-N curve S_a = a N^b, default 648e6 (mild steel, S_ut = 400 MPa: S = 0.9 S_ut at 1e3 "
             "cycles, S_e = 0.5 S_ut at 1e6, Shigley sect. 6-7); with a shaft given by its geometry the summary adds "
             "max_bending_stress_Pa (M c / I, M = k_b r L / 8), max_shear_stress_Pa (T c / J, T = k_tor gamma), "
             "max_von_mises_stress_Pa and Miner damage of rainflow cycles over the window: "
             "fatigue_damage_bending_miner (worst fibre), fatigue_damage_torsion_miner (sqrt(3) tau), "
             "fatigue_damage_miner (their sum)"},
            {"fatigue/sn_exponent", "b in [-1, -0.001], default -0.0851"},
            {"fatigue/endurance_limit_Pa", "S_e >= 0: smaller amplitudes do no damage, default 200e6"}};
  }

  std::unique_ptr<PreparedModel> Prepare(const JsonReader& r) const override {
    Rotor rotor;
    rotor.rotor_mass = r.Number("rotor_mass_kg", Range::Positive());
    rotor.rotor_inertia = r.Number("rotor_inertia_kgm2", Range::Positive());
    rotor.unbalance_mass = r.Number("unbalance_mass_kg", Range::NonNegative());
    rotor.eccentricity = r.Number("eccentricity_m", Range::NonNegative());
    const JsonReader shaft = r.Object("shaft");
    if (shaft.Has("bending_stiffness_N_per_m") || shaft.Has("torsional_stiffness_Nm_per_rad")) {
      rotor.bending_stiffness = shaft.Number("bending_stiffness_N_per_m", Range::Positive());
      rotor.torsional_stiffness = shaft.Number("torsional_stiffness_Nm_per_rad", Range::Positive());
    } else {
      const double d_o = shaft.Number("outer_diameter_m", Range::Positive());
      const double d_i = shaft.Number("inner_diameter_m", Range::NonNegative());
      if (d_i >= d_o) throw InputError(shaft.PathOf("inner_diameter_m"), "expected a value below outer_diameter_m");
      const double length = shaft.Number("length_m", Range::Positive());
      const double e_mod = shaft.Number("youngs_modulus_Pa", Range::Positive());
      const double g_mod = shaft.Number("shear_modulus_Pa", Range::Positive());
      const double area_moment = kPi / 64 * (std::pow(d_o, 4) - std::pow(d_i, 4));
      rotor.bending_stiffness = 192 * e_mod * area_moment / std::pow(length, 3);
      rotor.torsional_stiffness = g_mod * 2 * area_moment / length;  // polar J = 2 I for a round tube
      rotor.bending_stress_per_m = rotor.bending_stiffness * length / 8 * (d_o / 2) / area_moment;
      rotor.shear_stress_per_rad = rotor.torsional_stiffness * (d_o / 2) / (2 * area_moment);
    }
    shaft.Finish();
    if (r.Has("fatigue")) {
      const JsonReader sn = r.Object("fatigue");
      const analysis::SnCurve steel = analysis::SnCurve::MildSteel();
      rotor.sn_curve.coefficient_Pa = sn.Number("sn_coefficient_Pa", Range::Positive(), steel.coefficient_Pa);
      rotor.sn_curve.exponent = sn.Number("sn_exponent", Range::Between(-1, -1e-3), steel.exponent);
      rotor.sn_curve.endurance_limit_Pa = sn.Number("endurance_limit_Pa", Range::NonNegative(),
                                                    steel.endurance_limit_Pa);
      sn.Finish();
    }
    rotor.bending_damping_ratio = r.Number("bending_damping_ratio", Range::NonNegative());
    rotor.torsional_damping_ratio = r.Number("torsional_damping_ratio", Range::NonNegative());
    rotor.drive_speed = DriveSpeed(r, rotor.bending_frequency());
    rotor.torque = r.Has("torque_Nm") ? model::Schedule::FromJson(r.Raw("torque_Nm"), r.PathOf("torque_Nm"))
                                      : model::Schedule(0.0);
    r.Finish();
    return std::make_unique<JeffcottModel>(std::move(rotor));
  }
};

}  // namespace

std::unique_ptr<ModelKind> MakeJeffcottKind() { return std::make_unique<JeffcottKind>(); }

}  // namespace drillwave::cases
