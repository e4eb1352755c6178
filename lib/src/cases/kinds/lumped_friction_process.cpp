#include "lumped_friction_process.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "drillwave/bitrock/stick_slip.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/dynamics/contact.hpp"
#include "drillwave/integration/simulator.hpp"

namespace drillwave::cases::lumped {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
using bitrock::Turn;

// The Process of integration::Simulator for a Chain. Regimes: a bitrock::Turn per inertia; only
// inertias with a set-valued law (and no smoothing) ever stick. Everything that changes during a run lives here.
class ChainProcess : public integration::WithoutHistory {
 public:
  using State = std::vector<double>;

  explicit ChainProcess(const Chain& c) : c_(c), n_(static_cast<int>(c.inertias.size())), regime_(n_, Turn::kForward) {
    for (int i = 0; i < n_; ++i)
      if (CanStick(i)) frictional_.push_back(i);
    stuck_.resize(n_);
  }

  // State layout.
  int Twist(int j) const { return j; }
  int SpeedIndex(int i) const { return n_ - 1 + i; }
  int AngleIndex(int i) const { return 2 * n_ - 1 + i; }
  int Integral() const { return 3 * n_ - 1; }
  int Work() const { return 3 * n_; }
  int Dissipated() const { return 3 * n_ + 1; }
  int Load(int i) const { return 3 * n_ + 2 + i; }  // the friction scale of an inertia with a normal load
  int Dimension() const { return 4 * n_ + 2; }

  State InitialState(double t0) {
    State x(Dimension(), 0.0);
    if (Prescribed()) x[SpeedIndex(0)] = c_.setpoint.Value(t0);
    step_start_ = t0;
    // The load starts where the torque at rest, 0, puts it.
    for (int i = 0; i < n_; ++i)
      if (const auto& load = Inertia(i).normal_load) x[Load(i)] = LoadTarget(*load, Applied(i, t0), 0.0);
    // An inertia at rest sticks unless the torque on it already exceeds its static range.
    for (int i : frictional_) {
      regime_[i] = Turn::kStuck;
      regime_[i] = bitrock::TurnAtRest(AtRest(i, x, t0));
      if (regime_[i] == Turn::kStuck) stuck_[i].push_back({t0, kInf});
    }
    return x;
  }

  // --- Process interface -------------------------------------------------------------------------------------
  void BeginStep(double t0) { step_start_ = t0; }

  void Derivatives(const State& x, State& dx, double t) const {
    for (int j = 0; j + 1 < n_; ++j) dx[Twist(j)] = Speed(j, x, t) - Speed(j + 1, x, t);
    double dissipated = 0;
    for (int i = 0; i < n_; ++i) {
      const double v = Speed(i, x, t);
      dx[AngleIndex(i)] = v;
      const double friction = FrictionTorque(i, x, t);
      dissipated += Inertia(i).damping_Nms_per_rad * v * v + friction * v;
      if (i == 0 && Prescribed())
        dx[SpeedIndex(0)] = Setpoint(t).second;
      else
        dx[SpeedIndex(i)] = regime_[i] == Turn::kStuck ? 0.0 : (UnbalancedTorque(i, x, t, v) - friction) / Inertia(i).inertia_kgm2;
    }
    for (int j = 0; j + 1 < n_; ++j) {
      const double dv = Speed(j, x, t) - Speed(j + 1, x, t);
      dissipated += c_.couplings[j].damping_Nms_per_rad * dv * dv;
    }
    for (int i = 0; i < n_; ++i)
      if (const auto& load = Inertia(i).normal_load)
        dx[Load(i)] = (LoadTarget(*load, Applied(i, t), FrictionTorque(i, x, t)) - x[Load(i)]) / load->time_constant_s;
    dx[Integral()] = 0.0;
    if (c_.drive == Drive::kPiSpeed) {
      const double error = Setpoint(t).first - Speed(0, x, t);
      if (!c_.DriveIntegralHeld(c_.pi.Output(Setpoint(t).first, Speed(0, x, t), x[Integral()]), error))
        dx[Integral()] = error;
    }
    dx[Work()] = DriveTorque(x, t) * Speed(0, x, t);
    dx[Dissipated()] = dissipated;
  }

  int NumWitnesses() const { return 2 * static_cast<int>(frictional_.size()); }

  // Two witnesses per frictional inertia (bitrock/stick_slip.hpp).
  double Witness(int k, double t, const State& x) const {
    const int i = frictional_[k / 2];
    return bitrock::TurnWitness(regime_[i], k % 2, x[SpeedIndex(i)], [&] { return AtRest(i, x, t); });
  }

  bool OnEvent(int k, double t, State& x) {
    const int i = frictional_[k / 2];
    const Turn before = regime_[i];
    const Turn after = bitrock::TurnAfterEvent(before, k % 2, [&] {
      regime_[i] = Turn::kStuck;
      return AtRest(i, x, t);
    });
    regime_[i] = after;
    if (after == Turn::kStuck || before == Turn::kStuck) x[SpeedIndex(i)] = 0;
    if (after == Turn::kStuck && before != Turn::kStuck) stuck_[i].push_back({t, kInf});
    if (after != Turn::kStuck && before == Turn::kStuck && !stuck_[i].empty()) stuck_[i].back().end_s = t;
    return after != before;
  }

  double NextBreakpoint() const {
    double next = c_.setpoint.NextKnotAfter(passed_);
    for (const auto& in : c_.inertias) next = std::min(next, in.friction_scale.NextKnotAfter(passed_));
    return next;
  }
  void OnBreakpoint(double t) { passed_ = t; }

  // --- Torques and energies (also used for the outputs) -------------------------------------------------------
  double Speed(int i, const State& x, double t) const {
    if (i == 0 && Prescribed()) return Setpoint(t).first;
    return regime_[i] == Turn::kStuck ? 0.0 : x[SpeedIndex(i)];
  }
  double CouplingTorque(int j, const State& x, double t) const {
    const Coupling& cp = c_.couplings[j];
    return cp.stiffness_Nm_per_rad * x[Twist(j)] + cp.damping_Nms_per_rad * (Speed(j, x, t) - Speed(j + 1, x, t));
  }
  // The torque the drive puts into inertia 0. A prescribed speed takes whatever keeps inertia 0 on its set-point.
  double DriveTorque(const State& x, double t) const {
    if (Prescribed()) {
      const auto [w, dw] = Setpoint(t);
      return Inertia(0).inertia_kgm2 * dw - UnbalancedTorque(0, x, t, w);  // UnbalancedTorque(0) excludes the drive
    }
    return DriveTorqueAt(x, t, Speed(0, x, t));
  }
  // Friction torque on inertia i (opposing its motion); while stuck the torque that holds it.
  double FrictionTorque(int i, const State& x, double t) const {
    const auto& law = Inertia(i).friction;
    if (!law) return 0;
    if (regime_[i] == Turn::kStuck) return DrivingTorqueAtRest(i, x, t);
    return Contact(i).SlipTorque(regime_[i], Speed(i, x, t), Scale(i, x, t));
  }
  double StoredEnergy(const State& x, double t) const {
    double e = 0;
    for (int i = 0; i < n_; ++i) {
      const double v = Speed(i, x, t);
      e += 0.5 * Inertia(i).inertia_kgm2 * v * v;
    }
    for (int j = 0; j + 1 < n_; ++j) e += 0.5 * c_.couplings[j].stiffness_Nm_per_rad * x[Twist(j)] * x[Twist(j)];
    return e;
  }

  bool Stuck(int i) const { return regime_[i] == Turn::kStuck; }
  // The scale of inertia i's friction law: its schedule, or the state of its normal load (never below 0).
  double Scale(int i, const State& x, double t) const {
    return Inertia(i).normal_load ? std::max(x[Load(i)], 0.0) : Applied(i, t);
  }
  const std::vector<std::vector<StuckInterval>>& stuck_intervals() const { return stuck_; }

 private:
  const lumped::Inertia& Inertia(int i) const { return c_.inertias[i]; }
  bool Prescribed() const { return c_.drive == Drive::kPrescribedSpeed; }
  // Inertia i's contact with its friction law (which it must have).
  dynamics::Contact Contact(int i) const {
    return dynamics::Contact(*Inertia(i).friction, c_.friction_smoothing_rad_s);
  }
  bool CanStick(int i) const { return Inertia(i).friction && Contact(i).CanStick() && !(i == 0 && Prescribed()); }
  // Inputs on the side of the current step: right limits at its start, left limits inside and at its end (a step
  // never crosses a knot, so a jump or kink at the step's end belongs to the next step).
  std::pair<double, double> Setpoint(double t) const { return c_.setpoint.Evaluate(t, t > step_start_); }
  double Applied(int i, double t) const { return Inertia(i).friction_scale.Evaluate(t, t > step_start_).first; }
  static double LoadTarget(const NormalLoad& load, double applied, double torque) {
    return applied + load.gain_per_Nm * (torque - load.reference_Nm);
  }

  double DriveTorqueAt(const State& x, double t, double v0) const {
    const double u = Setpoint(t).first;
    switch (c_.drive) {
      case Drive::kTorque: return c_.torque_gain * u;
      case Drive::kPiSpeed: return c_.ClampedDriveTorque(c_.pi.Output(u, v0, x[Integral()]));
      case Drive::kPrescribedSpeed: break;
    }
    return 0;
  }
  // Every torque on inertia i except friction (and, for a prescribed-speed end, except the drive), with its speed
  // taken as v.
  double UnbalancedTorque(int i, const State& x, double t, double v) const {
    double torque = -Inertia(i).damping_Nms_per_rad * v;
    if (i == 0 && !Prescribed()) torque += DriveTorqueAt(x, t, v);
    if (i > 0) {
      const Coupling& cp = c_.couplings[i - 1];
      torque += cp.stiffness_Nm_per_rad * x[Twist(i - 1)] + cp.damping_Nms_per_rad * (Speed(i - 1, x, t) - v);
    }
    if (i + 1 < n_) {
      const Coupling& cp = c_.couplings[i];
      torque -= cp.stiffness_Nm_per_rad * x[Twist(i)] + cp.damping_Nms_per_rad * (v - Speed(i + 1, x, t));
    }
    return torque;
  }
  // What the friction must balance to hold inertia i at rest.
  double DrivingTorqueAtRest(int i, const State& x, double t) const { return UnbalancedTorque(i, x, t, 0.0); }
  // The torque on inertia i held at rest and the static range of its (scaled) friction.
  bitrock::AtRest AtRest(int i, const State& x, double t) const {
    return Contact(i).HeldAtRest(DrivingTorqueAtRest(i, x, t), Scale(i, x, t));
  }

  const Chain& c_;
  int n_;
  std::vector<Turn> regime_;
  std::vector<int> frictional_;
  std::vector<std::vector<StuckInterval>> stuck_;
  double step_start_ = 0;
  double passed_ = -kInf;
};

}  // namespace

void Chain::Validate() const {
  if (inertias.size() < 2) throw std::invalid_argument("a lumped chain needs at least two inertias");
  if (couplings.size() + 1 != inertias.size())
    throw std::invalid_argument("a lumped chain of n inertias needs n - 1 couplings");
  for (const auto& in : inertias) {
    if (!(in.inertia_kgm2 > 0) || !std::isfinite(in.inertia_kgm2)) throw std::invalid_argument("inertia must be > 0");
    if (!(in.damping_Nms_per_rad >= 0)) throw std::invalid_argument("damping must be >= 0");
    for (const auto& [t, s] : in.friction_scale.knots())
      if (!(s >= 0)) throw std::invalid_argument("friction scale must be >= 0");
  }
  for (const auto& cp : couplings)
    if (!(cp.stiffness_Nm_per_rad > 0) || !(cp.damping_Nms_per_rad >= 0))
      throw std::invalid_argument("coupling stiffness must be > 0 and damping >= 0");
  if (drive == Drive::kPrescribedSpeed && inertias[0].friction)
    throw std::invalid_argument("a prescribed-speed end takes no friction law (its drive torque covers it)");
  if (!(friction_smoothing_rad_s >= 0)) throw std::invalid_argument("friction smoothing must be >= 0");
  if (!(drive_torque_limit_Nm >= 0)) throw std::invalid_argument("the drive's torque limit must be >= 0");
  for (const auto& in : inertias) {
    if (!in.normal_load) continue;
    const NormalLoad& load = *in.normal_load;
    if (!in.friction) throw std::invalid_argument("a normal load needs a friction law to scale");
    if (!(load.time_constant_s > 0) || !(load.gain_per_Nm >= 0) || !std::isfinite(load.reference_Nm))
      throw std::invalid_argument("a normal load needs a time constant > 0, a gain >= 0 and a finite reference");
    if (!(load.gain_per_Nm * in.friction->StaticPositive() < 1))
      throw std::invalid_argument("a normal load's gain times the static friction level must stay below 1");
  }
}

double Chain::ClampedDriveTorque(double output) const {
  return drive_torque_limit_Nm > 0 ? std::clamp(output, -drive_torque_limit_Nm, drive_torque_limit_Nm) : output;
}

bool Chain::DriveIntegralHeld(double output, double speed_error) const {
  return drive_torque_limit_Nm > 0 && ((output > drive_torque_limit_Nm && speed_error > 0) ||
                                       (output < -drive_torque_limit_Nm && speed_error < 0));
}

bool Chain::HasNormalLoad() const {
  return std::any_of(inertias.begin(), inertias.end(), [](const Inertia& in) { return in.normal_load.has_value(); });
}

ChainRun RunChain(const Chain& chain, const RunSettings& settings) {
  chain.Validate();
  const int n = static_cast<int>(chain.inertias.size());
  ChainProcess process(chain);
  std::vector<double> x = process.InitialState(0.0);
  const double stored0 = process.StoredEnergy(x, 0.0);

  ChainRun run;
  run.speed_rad_s.resize(n), run.angle_rad.resize(n), run.friction_Nm.resize(n), run.stuck.resize(n);
  run.friction_scale.resize(n);
  run.coupling_torque_Nm.resize(n - 1);
  auto sample = [&](double t, const std::vector<double>& s) {
    run.time_s.push_back(t);
    for (int i = 0; i < n; ++i) {
      run.speed_rad_s[i].push_back(process.Speed(i, s, t));
      run.angle_rad[i].push_back(s[process.AngleIndex(i)]);
      run.friction_Nm[i].push_back(process.FrictionTorque(i, s, t));
      run.stuck[i].push_back(process.Stuck(i) ? 1.0 : 0.0);
      run.friction_scale[i].push_back(process.Scale(i, s, t));
    }
    for (int j = 0; j + 1 < n; ++j) run.coupling_torque_Nm[j].push_back(process.CouplingTorque(j, s, t));
    run.drive_torque_Nm.push_back(process.DriveTorque(s, t));
    run.energy_residual_J.push_back(s[process.Work()] - s[process.Dissipated()] -
                                    (process.StoredEnergy(s, t) - stored0));
  };
  sample(0.0, x);
  const auto observer = integration::SampleEvery(settings.output_interval_s, sample);
  integration::Simulator<ChainProcess> sim(process, settings.integrator);
  const std::vector<double> x_end = sim.Integrate(0.0, x, settings.duration_s, observer);

  run.stuck_intervals = process.stuck_intervals();
  run.stats = sim.stats();
  run.work_in_J = x_end[process.Work()];
  run.dissipated_J = x_end[process.Dissipated()];
  run.stored_change_J = process.StoredEnergy(x_end, settings.duration_s) - stored0;
  return run;
}

RunResult ChainResult(const ChainRun& run, const RunSettings& settings) {
  const std::size_t bit = run.speed_rad_s.size() - 1;
  RunResult result;
  result.time_s = run.time_s;
  result.channels = {{"top_rpm", ToRpm(run.speed_rad_s[0])},
                     {"bit_rpm", ToRpm(run.speed_rad_s[bit])},
                     {"top_torque_Nm", run.coupling_torque_Nm[0]},
                     {"bit_torque_Nm", run.friction_Nm[bit]},
                     {"bit_angle_rad", run.angle_rad[bit]},
                     {"bit_stuck", run.stuck[bit]},
                     {"drive_torque_Nm", run.drive_torque_Nm},
                     {"energy_balance_residual_J", run.energy_residual_J}};
  result.plot_panels = {{"top_rpm", "bit_rpm"}, {"top_torque_Nm", "bit_torque_Nm"}};
  result.summary = ComputeStickSlipStatistics(run.stuck_intervals[bit], run.time_s, run.speed_rad_s[bit],
                                              run.angle_rad[bit], settings.window_begin_s, settings.window_end_s)
                       .ToJson();
  double worst = 0;
  for (double b : run.energy_residual_J) worst = std::max(worst, std::abs(b));
  result.summary["energy_balance_residual_max_J"] = worst;
  result.summary["work_in_J"] = run.work_in_J;
  result.summary["steps"] = run.stats.steps;
  result.summary["events"] = run.stats.events;
  result.summary["derivative_evaluations"] = run.stats.derivative_evaluations;
  return result;
}

namespace {

// Friction and damper torque on inertia i sliding forwards at w (final input values), and its slope.
std::pair<double, double> SlidingTorque(const Chain& c, int i, double w) {
  const Inertia& in = c.inertias[i];
  double torque = in.damping_Nms_per_rad * w, slope = in.damping_Nms_per_rad;
  if (in.friction) {
    const double scale = in.friction_scale.knots().back().second;
    double t = in.friction->SlipTorque(w), dt = in.friction->SlipTorqueDerivative(w);
    if (c.friction_smoothing_rad_s > 0) {
      const double th = std::tanh(w / c.friction_smoothing_rad_s);
      dt = dt * th + t * (1 - th * th) / c.friction_smoothing_rad_s;
      t *= th;
    }
    torque += scale * t;
    slope += scale * dt;
  }
  return {torque, slope};
}

}  // namespace

std::vector<LinearizedOperatingPoint> LinearizeChain(const Chain& c) {
  c.Validate();
  const int n = static_cast<int>(c.inertias.size());
  const double u = c.setpoint.knots().back().second;
  auto total = [&](double w) {
    double sum = 0;
    for (int i = 0; i < n; ++i) sum += SlidingTorque(c, i, w).first;
    return sum;
  };
  // Steady speeds.
  std::vector<double> speeds;
  if (c.drive != Drive::kTorque) {
    if (u > 0) speeds.push_back(u);
  } else {
    const double drive = c.torque_gain * u;
    double hi = 1.0;
    while (total(hi) < drive && hi < 1e9) hi *= 2;
    const int samples = 20000;
    double w_prev = hi * 1e-12, f_prev = drive - total(w_prev);
    for (int k = 1; k <= samples; ++k) {
      const double w = hi * k / samples, f = drive - total(w);
      if ((f_prev > 0) != (f > 0)) {
        double lo = w_prev, up = w, flo = f_prev;
        for (int it = 0; it < 200 && up - lo > 1e-15 * up; ++it) {
          const double mid = 0.5 * (lo + up), fm = drive - total(mid);
          if ((fm > 0) == (flo > 0)) lo = mid, flo = fm; else up = mid;
        }
        speeds.push_back(0.5 * (lo + up));
      }
      w_prev = w, f_prev = f;
    }
  }

  std::vector<LinearizedOperatingPoint> points;
  const bool prescribed = c.drive == Drive::kPrescribedSpeed, pi = c.drive == Drive::kPiSpeed;
  for (double w : speeds) {
    // A steady state whose torque lies beyond the drive's limit is not one the limited drive can hold.
    if (c.drive == Drive::kPiSpeed && c.drive_torque_limit_Nm > 0 && total(w) > c.drive_torque_limit_Nm) continue;
    // State indices: twists 0..n-2, then the speeds of the inertias that move freely, then the PI integral.
    std::vector<int> speed_index(n, -1);
    std::vector<std::string> names;
    for (int j = 0; j + 1 < n; ++j) names.push_back("twist_" + std::to_string(j) + "_rad");
    for (int i = prescribed ? 1 : 0; i < n; ++i) {
      speed_index[i] = static_cast<int>(names.size());
      names.push_back("speed_" + std::to_string(i) + "_rad_s");
    }
    const int integral = pi ? static_cast<int>(names.size()) : -1;
    if (pi) names.push_back("pi_integral_rad");
    const int m = static_cast<int>(names.size());
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(m, m);
    auto add_speed = [&](int row, int i, double factor) {
      if (speed_index[i] >= 0) a(row, speed_index[i]) += factor;
    };
    for (int j = 0; j + 1 < n; ++j) add_speed(j, j, 1), add_speed(j, j + 1, -1);
    std::vector<double> slopes(n), twists(n > 1 ? n - 1 : 0);
    double transmitted = 0;  // steady torque through coupling j: everything below it
    for (int i = n - 1; i >= 0; --i) {
      const auto [torque, slope] = SlidingTorque(c, i, w);
      slopes[i] = slope;
      if (i > 0) transmitted += torque, twists[i - 1] = transmitted / c.couplings[i - 1].stiffness_Nm_per_rad;
      if (speed_index[i] < 0) continue;
      const int row = speed_index[i];
      const double inv = 1.0 / c.inertias[i].inertia_kgm2;
      add_speed(row, i, -slope * inv);
      if (i > 0) {
        const Coupling& cp = c.couplings[i - 1];
        a(row, i - 1) += cp.stiffness_Nm_per_rad * inv;
        add_speed(row, i - 1, cp.damping_Nms_per_rad * inv);
        add_speed(row, i, -cp.damping_Nms_per_rad * inv);
      }
      if (i + 1 < n) {
        const Coupling& cp = c.couplings[i];
        a(row, i) -= cp.stiffness_Nm_per_rad * inv;
        add_speed(row, i, -cp.damping_Nms_per_rad * inv);
        add_speed(row, i + 1, cp.damping_Nms_per_rad * inv);
      }
      if (i == 0 && pi) {
        add_speed(row, 0, -c.pi.kp * inv);
        a(row, integral) += c.pi.ki * inv;
      }
    }
    if (pi) add_speed(integral, 0, -1);
    nlohmann::json steady = {{"speed_rad_s", w}, {"twists_rad", twists}, {"torque_slopes_Nms_per_rad", slopes}};
    steady["drive_torque_Nm"] = total(w);
    points.push_back({steady, names, analysis::LinearDelaySystem{a, {}}});
  }
  return points;
}

double ReadFrictionSmoothing(const io::JsonReader& model) {
  const double eps = model.Number("friction_smoothing_rad_s", io::Range::NonNegative(), 0.0);
  // tanh(w / eps) has the slope T / eps at w = 0: below a micro-radian per second the smoothed law is a stiffness
  // no explicit step resolves (1e-300 asked for 1e8 evaluations in 0.01 s), and 0 already is the exact limit.
  if (eps > 0 && eps < kMinFrictionSmoothing_rad_s)
    throw InputError(model.PathOf("friction_smoothing_rad_s"),
                     "expected 0 (set-valued friction, exact stick phases) or a smoothing speed >= 1e-6 rad/s, got " +
                         ReadableNumber(eps));
  return eps;
}

}  // namespace drillwave::cases::lumped
