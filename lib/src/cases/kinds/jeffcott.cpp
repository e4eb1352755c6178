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

#include "drillwave/cases/kinds.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/integration/simulator.hpp"
#include "drillwave/model/schedule.hpp"

namespace drillwave::cases {
namespace {

using io::JsonReader;
using Range = io::Range;
constexpr double kPi = 3.14159265358979323846;

struct Rotor {
  double rotor_mass = 1, rotor_inertia = 1, unbalance_mass = 0, eccentricity = 0;
  double bending_stiffness = 1, torsional_stiffness = 1;
  double bending_damping_ratio = 0, torsional_damping_ratio = 0;
  model::Schedule drive_speed;  // theta'(t) [rad/s]
  model::Schedule torque;       // T(t) on the rotor [N·m]; negative: a reverse (braking) torque

  double mass() const { return rotor_mass + unbalance_mass; }
  double inertia() const { return rotor_inertia + unbalance_mass * eccentricity * eccentricity; }
  double bending_frequency() const { return std::sqrt(bending_stiffness / mass()); }        // w_b [rad/s]
  double torsional_frequency() const { return std::sqrt(torsional_stiffness / inertia()); }  // w_tor [rad/s]
  double bending_damping() const { return 2 * bending_damping_ratio * bending_frequency() * mass(); }
  double torsional_damping() const { return 2 * torsional_damping_ratio * torsional_frequency() * inertia(); }
};

// State: x, y, gamma, x', y', gamma', theta.
class RotorProcess {
 public:
  using State = std::vector<double>;
  explicit RotorProcess(const Rotor& r) : r_(r), c_b_(r.bending_damping()), c_tor_(r.torsional_damping()) {}

  int Dimension() const { return 7; }
  double MaxStep() const { return std::numeric_limits<double>::infinity(); }
  void BeginStep(double t0) { step_start_ = t0; }
  double PrepareCommit(const integration::Piece&, double, double) { return 0; }
  void Commit(const integration::Piece&) {}
  int NumWitnesses() const { return 0; }
  double Witness(int, double, const State&) const { return 1; }
  bool OnEvent(int, double, State&) { return false; }
  double NextBreakpoint() const {
    double next = std::numeric_limits<double>::infinity();
    for (const model::Schedule* s : {&r_.drive_speed, &r_.torque})
      for (const auto& knot : s->knots())
        if (knot.first > passed_) next = std::min(next, knot.first);
    return next;
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

class JeffcottModel : public PreparedModel {
 public:
  explicit JeffcottModel(Rotor r) : r_(std::move(r)) {}

  RunResult Run(const RunSettings& settings) const override {
    RotorProcess process(r_);
    std::vector<double> x(7, 0.0);
    std::vector<double> time, xs, ys, radius, twist, drive, rotor, shaft_torque, torque, normalized;
    auto sample = [&](double t, const std::vector<double>& s) {
      const double omega = process.Drive(t).first, beta_dot = omega + s[5];
      time.push_back(t), xs.push_back(s[0]), ys.push_back(s[1]), radius.push_back(std::hypot(s[0], s[1]));
      twist.push_back(s[2]), drive.push_back(omega), rotor.push_back(beta_dot);
      shaft_torque.push_back(r_.torsional_stiffness * s[2] + process.TorsionalDamping() * s[5]);
      torque.push_back(r_.torque.Value(t));
      normalized.push_back(omega != 0 ? beta_dot / omega : beta_dot == 0 ? 1.0 : std::nan(""));  // at rest: 1
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
    for (std::size_t i = 0; i < time.size(); ++i) {
      if (time[i] < settings.window_begin_s || time[i] > settings.window_end_s) continue;
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
            {"torque_Nm", "external torque on the rotor, schedule, default 0 (negative: reverse / brake torque)"}};
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
    }
    shaft.Finish();
    rotor.bending_damping_ratio = r.Number("bending_damping_ratio", Range::NonNegative());
    rotor.torsional_damping_ratio = r.Number("torsional_damping_ratio", Range::NonNegative());
    rotor.drive_speed = model::Schedule::FromJson(r.Raw("drive_speed_rad_s"), r.PathOf("drive_speed_rad_s"));
    rotor.torque = r.Has("torque_Nm") ? model::Schedule::FromJson(r.Raw("torque_Nm"), r.PathOf("torque_Nm"))
                                      : model::Schedule(0.0);
    r.Finish();
    return std::make_unique<JeffcottModel>(std::move(rotor));
  }
};

}  // namespace

std::unique_ptr<ModelKind> MakeJeffcottKind() { return std::make_unique<JeffcottKind>(); }

}  // namespace drillwave::cases
