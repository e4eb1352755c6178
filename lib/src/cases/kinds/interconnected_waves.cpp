// Model kind "interconnected_waves": the chapter seed's sect. 2.5 model (eqs. 2.12-2.13), an axial and a torsional
// wave equation in one uniform pipe, each with a dissipative top, coupled only at the bit, where the torque on bit is a
// function of the bit's axial speed:
//   U_tt = c^2 U_ss,  E Gamma U_s(t, 0) = alpha1 U_t(t, 0) - alpha2 H(t),      M U_tt(t, L) = -E Gamma U_s(t, L) - F(U_t(t, L))
//   Phi_tt = c~^2 Phi_ss,  G Sigma Phi_s(t, 0) = beta1 Phi_t(t, 0) - beta2 Omega(t),
//                                                                J Phi_tt(t, L) = -G Sigma Phi_s(t, L) - F~(U_t(t, L))
// s runs down from the top (s = 0) to the bit (s = L); U is positive down, so H > 0 pushes the string down (the
// chapter's top boundary as written: in steady motion U_s = -F / (E Gamma), and the top gives alpha1 v = alpha2 H - F).
// Sign convention at the bit: the chapter writes "+ F(...)"; here F and F~ are the friction laws' values (positive for
// a positive speed) taken as resisting, so they enter with a minus: the weight on bit F(v) opposes the bit's descent and
// the torque on bit F~(v) its rotation.
//
// d'Alembert (DESIGN.md §1), per channel with impedance Z (Gamma sqrt(E rho), Sigma sqrt(G rho)) and travel time
// tau = L / c: speed q_t = D + Up, force K q_s = Z (Up - D). The top's boundary gives the down-going wave it sends,
// D(t, 0) = r Up(t, 0) + g I(t) / (Z + d), with r = (Z - d) / (Z + d) (d = alpha1 or beta1, g = alpha2 or beta2, I = H or
// Omega). Up(t, 0) is the bit's up-going wave v - w one travel time earlier, so the wave w arriving at the bit is
//   w(t) = r (v(t - 2 tau) - w(t - 2 tau)) + g I(t - tau) / (Z + d),
// and the bit's law of motion, with -K q_s(L) = Z (2 w - v):
//   M v' = Z_a (2 w_a - v) - F(v),   J omega' = Z_t (2 w_t - omega) - F~(v).
// Steady state: alpha1 v = alpha2 H - F(v), beta1 omega = beta2 Omega - F~(v).
//
// Integration: the generic delay solver (integration/delay_solver.hpp) in its neutral form. The wave arriving at the bit
// two travel times ago is recovered from the bit's own law of motion then, w = (M v' + Z v + F) / (2 Z), so the state
// is only the bit's speeds (and its depth and angle for the outputs), and the past is read through v and v'. The string
// is at rest before t = 0 and the inputs are switched on at t = 0 (H and Omega read as 0 before it); the jump this
// makes arrives at the bit tau later, a breakpoint the solver propagates. The inputs' knots reach the bit a travel time
// after they leave the top: each arrival is an event, so the solver steps onto it and follows its kink.
//
// Linearization (`drillwave stability`): about every steady state at the inputs' last knots, a 2-state neutral system
// whose characteristic function is the product of the two channels' (derived above LinearSystem below).
//
// Friction laws: smooth ones only. Set-valued laws would need stuck regimes of the axial bit, and the torque on bit,
// a function of the axial speed, has no static range of its own to hold the rotation.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>

#include "drillwave/cases/friction_json.hpp"
#include "drillwave/cases/kinds.hpp"
#include "drillwave/cases/statistics.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/integration/delay_solver.hpp"
#include "drillwave/model/schedule.hpp"

namespace drillwave::cases {
namespace {

using integration::PastView;
using io::JsonReader;
using Range = io::Range;

// One wave channel of the pipe (axial: speed [m/s], force [N]; torsional: [rad/s], [N m]) between its dissipative top
// and the bit's inertia.
struct WaveChannel {
  double impedance = 0;    // Z
  double travel_time = 0;  // tau = L / c
  double top_damping = 0;  // alpha1 or beta1
  double top_gain = 0;     // alpha2 or beta2
  double bit_inertia = 0;  // M or J
  model::Schedule input;   // H(t) or Omega(t), 0 before t = 0

  double Reflection() const { return (impedance - top_damping) / (impedance + top_damping); }
  double Input(double t) const { return t < 0 ? 0.0 : input.Value(t); }
  // The down-going wave the top sends at t when the up-going wave `up` arrives there.
  double TopSends(double up, double t) const {
    return Reflection() * up + top_gain * Input(t) / (impedance + top_damping);
  }
  // The up-going wave the bit sends at speed v, acceleration dv and resisting load: v minus the arriving wave, which
  // the bit's law of motion I v' = Z (2 w - v) - load gives.
  double BitSends(double v, double dv, double load) const {
    return v - (bit_inertia * dv + impedance * v + load) / (2 * impedance);
  }
  double BitAcceleration(double arriving, double v, double load) const {
    return (impedance * (2 * arriving - v) - load) / bit_inertia;
  }
};

// State: the bit's axial speed and angular speed, then its depth and angle (outputs only).
enum Index { kAxialSpeed = 0, kAngularSpeed, kDepth, kAngle, kDimension };

// The two channels, numbered as the bit's speeds in the state.
enum Wave { kAxial = kAxialSpeed, kTorsional = kAngularSpeed };

struct Model {
  WaveChannel axial, torsion;
  std::optional<bitrock::FrictionLaw> weight_law, torque_law;  // F and F~ of the bit's axial speed; absent: 0

  const WaveChannel& Channel(Wave w) const { return w == kAxial ? axial : torsion; }
  double WeightOnBit(double axial_speed) const { return weight_law ? weight_law->SlipTorque(axial_speed) : 0.0; }
  double TorqueOnBit(double axial_speed) const { return torque_law ? torque_law->SlipTorque(axial_speed) : 0.0; }
  // What resists the bit in channel w: both loads follow the axial speed.
  double Load(Wave w, double axial_speed) const {
    return w == kAxial ? WeightOnBit(axial_speed) : TorqueOnBit(axial_speed);
  }
};

// The up-going wave the bit sent at s (the string at rest before t = 0: all zero there), read at t through `past`.
double BitSentAt(const Model& md, Wave w, double s, double t, const PastView& past) {
  return md.Channel(w).BitSends(past.Value(s, w, t), past.Derivative(s, w, t),
                                md.Load(w, past.Value(s, kAxialSpeed, t)));
}

// The wave arriving at the bit at t: what the top sent one travel time earlier.
double ArrivingAtBit(const Model& md, Wave w, double t, const PastView& past) {
  const WaveChannel& c = md.Channel(w);
  const double sent = t - c.travel_time;
  return c.TopSends(BitSentAt(md, w, sent - c.travel_time, t, past), sent);
}

// The top's speed at t, and what the top feeds into the string there (alpha2 H - alpha1 v_top, down positive; or the
// torque beta2 Omega - beta1 omega_top).
struct TopEnd {
  double speed, drive;
};
TopEnd TopAt(const Model& md, Wave w, double t, const PastView& past) {
  const WaveChannel& c = md.Channel(w);
  const double up = BitSentAt(md, w, t - c.travel_time, t, past);
  const double speed = up + c.TopSends(up, t);
  return {speed, c.top_gain * c.Input(t) - c.top_damping * speed};
}

// The pure right-hand side: the bit's two laws of motion.
void Rates(const Model& md, double t, const std::vector<double>& x, const PastView& past, std::vector<double>& dx) {
  const double v = x[kAxialSpeed], omega = x[kAngularSpeed];
  dx[kAxialSpeed] = md.axial.BitAcceleration(ArrivingAtBit(md, kAxial, t, past), v, md.WeightOnBit(v));
  dx[kAngularSpeed] = md.torsion.BitAcceleration(ArrivingAtBit(md, kTorsional, t, past), omega, md.TorqueOnBit(v));
  dx[kDepth] = v;
  dx[kAngle] = omega;
}

// The times (> 0) at which the input's knots after t = 0 reach the bit.
std::vector<double> KnotArrivals(const WaveChannel& c) {
  std::vector<double> arrivals;
  for (const auto& [time, value] : c.input.knots())
    if (time > 0 && (arrivals.empty() || time + c.travel_time > arrivals.back()))
      arrivals.push_back(time + c.travel_time);
  return arrivals;
}

integration::DelayProblem MakeProblem(const Model& md) {
  integration::DelayProblem p;
  p.dimension = kDimension;
  p.history = [](double, double* value, double* derivative) {
    std::fill(value, value + kDimension, 0.0);
    std::fill(derivative, derivative + kDimension, 0.0);
  };
  p.rhs = [&md](double t, const std::vector<double>& x, const PastView& past, const integration::DelayProblem::Mode&,
                std::vector<double>& dx) { Rates(md, t, x, past, dx); };
  p.constant_delays = {md.axial.travel_time, 2 * md.axial.travel_time, md.torsion.travel_time,
                       2 * md.torsion.travel_time};
  p.neutral = true;
  // Mode k: how many of input k's knot arrivals have passed; its witness is the time left to the next one.
  p.initial_mode = {0, 0};
  for (const Wave w : {kAxial, kTorsional}) {
    const int k = static_cast<int>(p.witnesses.size());
    p.witnesses.push_back([k, arrivals = KnotArrivals(md.Channel(w))](double t, const std::vector<double>&, const PastView&,
                                                            const integration::DelayProblem::Mode& mode) {
      return mode[k] < static_cast<int>(arrivals.size()) ? arrivals[mode[k]] - t : 1.0;
    });
  }
  p.on_event = [](int k, double, std::vector<double>&, integration::DelayProblem::Mode& mode) { ++mode[k]; };
  return p;
}

struct Samples {
  std::vector<double> time, bit_axial_speed, bit_speed, top_axial_speed, top_speed, wob, bit_torque, hook_force,
      top_force, top_torque, depth, angle;
};

Samples Sample(const Model& md, const integration::DelaySolution& solution, double t_end, double interval) {
  Samples s;
  const auto n = static_cast<long>(std::floor(t_end / interval + 1e-9));
  for (long i = 0; i <= n; ++i) {
    const double t = std::min(i * interval, t_end);
    const PastView past(solution.trajectory, t);  // right limits at t
    const double v = past.Value(t, kAxialSpeed, t);
    const TopEnd axial_top = TopAt(md, kAxial, t, past), torsion_top = TopAt(md, kTorsional, t, past);
    s.time.push_back(t);
    s.bit_axial_speed.push_back(v);
    s.bit_speed.push_back(past.Value(t, kAngularSpeed, t));
    s.top_axial_speed.push_back(axial_top.speed);
    s.top_speed.push_back(torsion_top.speed);
    s.wob.push_back(md.WeightOnBit(v));
    s.bit_torque.push_back(md.TorqueOnBit(v));
    s.hook_force.push_back(md.axial.Input(t));
    s.top_force.push_back(axial_top.drive);
    s.top_torque.push_back(torsion_top.drive);
    s.depth.push_back(past.Value(t, kDepth, t));
    s.angle.push_back(past.Value(t, kAngle, t));
  }
  return s;
}

// Mean, smallest and largest sample in [begin, end], under "<name>_mean<unit>" etc.
void AddWindowStatistics(const std::vector<double>& time, const std::vector<double>& values, double begin, double end,
                         const std::string& name, const std::string& unit, nlohmann::json& summary) {
  double sum = 0, lo = std::numeric_limits<double>::infinity(), hi = -lo;
  int n = 0;
  for (std::size_t i = 0; i < time.size(); ++i)
    if (time[i] >= begin && time[i] <= end) sum += values[i], lo = std::min(lo, values[i]), hi = std::max(hi, values[i]), ++n;
  summary[name + "_mean" + unit] = n ? sum / n : 0.0;
  summary[name + "_min" + unit] = n ? lo : 0.0;
  summary[name + "_max" + unit] = n ? hi : 0.0;
}

// --- Linearization (drillwave stability) ------------------------------------------------------------------------------
// About steady drilling (v*, omega*) at the inputs' final values (constant I), with y, W the bit's speed perturbations,
// the arriving waves' perturbations are what the bit's laws of motion give,
//   w_a = (M y' + (Z_a + F') y) / (2 Z_a),   w_t = (J W' + Z_t W + F~' y) / (2 Z_t)   (F' = F'(v*), F~' = F~'(v*)),
// and each obeys the channel's round trip w(t) = r (speed(t - 2 tau) - w(t - 2 tau)). Substituting, per channel:
//   y' + r_a y'(t - 2 tau_a) = -(Z_a + F') / M y + r_a (Z_a - F') / M y(t - 2 tau_a),
//   W' + r_t W'(t - 2 tau_t) = -Z_t / J W + r_t Z_t / J W(t - 2 tau_t) - F~' / J (y + r_t y(t - 2 tau_t)).
// The torsional row is driven by the axial one and does not feed back (triangular), so
//   det Delta(s) = [(M s + Z_a + F')(1 + r_a e^{-2 s tau_a}) - 2 Z_a r_a e^{-2 s tau_a}]
//                * [(J s + Z_t)(1 + r_t e^{-2 s tau_t}) - 2 Z_t r_t e^{-2 s tau_t}] / (M J),
// and the difference operator is diagonal: its essential spectrum lies at Re s = ln|r| / (2 tau) per channel (the
// robust abscissa of two incommensurate delays is their maximum). At s = 0 the axial factor is 2 Z_a (alpha1 + F') /
// (Z_a + alpha1): a steady state where alpha1 + F' < 0 (the falling side of a humped law) has a real root s > 0.

double FinalInput(const WaveChannel& c) { return c.input.knots().back().second; }

double WeightSlope(const Model& md, double v) { return md.weight_law ? md.weight_law->SlipTorqueDerivative(v) : 0.0; }
double TorqueSlope(const Model& md, double v) { return md.torque_law ? md.torque_law->SlipTorqueDerivative(v) : 0.0; }

// The root in [lo, hi] of f, whose signs differ there, by bisection to rounding.
double Bisect(const std::function<double(double)>& f, double lo, double hi) {
  const bool rising = f(hi) > 0;
  for (int i = 0; i < 200 && hi - lo > 1e-15 * std::max(std::abs(lo), std::abs(hi)); ++i) {
    const double mid = 0.5 * (lo + hi);
    ((f(mid) > 0) == rising ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

// Every v with alpha1 v + F(v) = alpha2 H at the final H, ascending. alpha1 v + F(v) need not be monotone (a humped F
// gives up to three roots): sign changes on a grid geometric in |v| on either side of 0 (relative spacing 0.5 %, from
// 1e-9 of a bound beyond which alpha1 v dominates), refined by bisection.
std::vector<double> SteadyAxialSpeeds(const Model& md) {
  const double drive = md.axial.top_gain * FinalInput(md.axial);
  const std::function<double(double)> excess = [&](double v) {
    return md.axial.top_damping * v + md.WeightOnBit(v) - drive;
  };
  double bound = 1.0;
  while ((excess(bound) <= 0 || excess(-bound) >= 0) && bound < 1e12) bound *= 2;
  constexpr int kPerSide = 4000;
  std::vector<double> grid;
  for (int i = kPerSide; i >= 0; --i) grid.push_back(-bound * std::pow(1e-9, static_cast<double>(i) / kPerSide));
  grid.push_back(0.0);
  for (int i = kPerSide; i >= 0; --i) grid.push_back(bound * std::pow(1e-9, static_cast<double>(i) / kPerSide));
  std::vector<double> speeds;
  for (std::size_t i = 1; i < grid.size(); ++i) {
    const double before = excess(grid[i - 1]), after = excess(grid[i]);
    if (after == 0) speeds.push_back(grid[i]);
    else if (before != 0 && (before > 0) != (after > 0)) speeds.push_back(Bisect(excess, grid[i - 1], grid[i]));
  }
  return speeds;
}

// The neutral system of the file's linearization about the bit's steady axial speed v.
analysis::LinearDelaySystem LinearSystem(const Model& md, double v) {
  const WaveChannel &a = md.axial, &t = md.torsion;
  const double slope = WeightSlope(md, v), coupling = TorqueSlope(md, v) / t.bit_inertia;
  const double ra = a.Reflection(), rt = t.Reflection();
  analysis::LinearDelaySystem sys;
  sys.a0 = Eigen::MatrixXd::Zero(2, 2);
  sys.a0(kAxial, kAxial) = -(a.impedance + slope) / a.bit_inertia;
  sys.a0(kTorsional, kTorsional) = -t.impedance / t.bit_inertia;
  sys.a0(kTorsional, kAxial) = -coupling;
  analysis::DelayTerm axial{2 * a.travel_time, Eigen::MatrixXd::Zero(2, 2), Eigen::MatrixXd::Zero(2, 2)};
  axial.retarded(kAxial, kAxial) = ra * (a.impedance - slope) / a.bit_inertia;
  axial.neutral(kAxial, kAxial) = -ra;
  analysis::DelayTerm torsional{2 * t.travel_time, Eigen::MatrixXd::Zero(2, 2), Eigen::MatrixXd::Zero(2, 2)};
  torsional.retarded(kTorsional, kTorsional) = rt * t.impedance / t.bit_inertia;
  torsional.retarded(kTorsional, kAxial) = -rt * coupling;
  torsional.neutral(kTorsional, kTorsional) = -rt;
  sys.delays = {std::move(axial), std::move(torsional)};
  return sys;
}

// Where a channel's difference operator puts its essential spectrum: ln|r| / (2 tau) (-inf for a matched top, r = 0).
double EssentialAbscissa(const WaveChannel& c) { return std::log(std::abs(c.Reflection())) / (2 * c.travel_time); }

LinearizedOperatingPoint LinearizeAt(const Model& md, double v) {
  const double omega = (md.torsion.top_gain * FinalInput(md.torsion) - md.TorqueOnBit(v)) / md.torsion.top_damping;
  nlohmann::json steady = {{"hook_force_N", FinalInput(md.axial)},
                           {"top_speed_setpoint_rad_s", FinalInput(md.torsion)},
                           {"bit_axial_speed_m_s", v},
                           {"rop_m_h", 3600 * v},
                           {"bit_speed_rad_s", omega},
                           {"wob_N", md.WeightOnBit(v)},
                           {"bit_torque_Nm", md.TorqueOnBit(v)},
                           {"wob_slope_Ns_per_m", WeightSlope(md, v)},
                           {"bit_torque_slope_Nms_per_m", TorqueSlope(md, v)}};
  for (const auto& [name, c] : {std::pair{"axial", &md.axial}, std::pair{"torsional", &md.torsion}}) {
    const double essential = EssentialAbscissa(*c);
    steady[std::string(name) + "_top_reflection"] = c->Reflection();
    steady[std::string(name) + "_round_trip_s"] = 2 * c->travel_time;
    steady[std::string(name) + "_essential_abscissa_per_s"] = std::isfinite(essential) ? nlohmann::json(essential)
                                                                                      : nlohmann::json(nullptr);
  }
  return {std::move(steady), {"bit_axial_speed_m_s", "bit_speed_rad_s"}, LinearSystem(md, v)};
}

class InterconnectedWavesModel : public PreparedModel {
 public:
  explicit InterconnectedWavesModel(Model md) : md_(std::move(md)) {}

  // Every steady drilling state at the inputs' final values, with its linearization (see above).
  std::vector<LinearizedOperatingPoint> Linearize() const override {
    std::vector<LinearizedOperatingPoint> points;
    for (const double v : SteadyAxialSpeeds(md_)) points.push_back(LinearizeAt(md_, v));
    return points;
  }

  RunResult Run(const RunSettings& settings) const override {
    const integration::DelayProblem problem = MakeProblem(md_);
    const integration::DelaySolution solution =
        integration::SolveDelayProblem(problem, settings.duration_s, settings.integrator);
    Samples s = Sample(md_, solution, settings.duration_s, settings.output_interval_s);
    RunResult result;
    result.summary = Summary(s, settings, solution.stats);
    result.channels = {{"top_rpm", ToRpm(s.top_speed)},
                       {"bit_rpm", ToRpm(s.bit_speed)},
                       {"top_torque_Nm", std::move(s.top_torque)},
                       {"bit_torque_Nm", std::move(s.bit_torque)},
                       {"bit_angle_rad", std::move(s.angle)},
                       {"top_axial_speed_m_s", std::move(s.top_axial_speed)},
                       {"bit_axial_speed_m_s", std::move(s.bit_axial_speed)},
                       {"hook_force_N", std::move(s.hook_force)},
                       {"top_force_N", std::move(s.top_force)},
                       {"wob_N", std::move(s.wob)},
                       {"bit_depth_m", std::move(s.depth)}};
    result.plot_panels = {{"top_rpm", "bit_rpm"},
                          {"top_torque_Nm", "bit_torque_Nm"},
                          {"top_axial_speed_m_s", "bit_axial_speed_m_s"},
                          {"hook_force_N", "top_force_N", "wob_N"}};
    result.time_s = std::move(s.time);
    return result;
  }

 private:
  nlohmann::json Summary(const Samples& s, const RunSettings& settings, const integration::IntegrationStats& stats) const {
    const double begin = settings.window_begin_s, end = settings.window_end_s;
    nlohmann::json summary = ComputeStickSlipStatistics({}, s.time, s.bit_speed, s.angle, begin, end).ToJson();
    AddWindowStatistics(s.time, s.bit_axial_speed, begin, end, "bit_axial_speed", "_m_s", summary);
    AddWindowStatistics(s.time, s.wob, begin, end, "wob", "_N", summary);
    AddWindowStatistics(s.time, s.bit_torque, begin, end, "bit_torque", "_Nm", summary);
    AddWindowStatistics(s.time, s.top_speed, begin, end, "top_speed", "_rad_s", summary);
    for (const auto& [name, c] : {std::pair{"axial", &md_.axial}, std::pair{"torsional", &md_.torsion}}) {
      summary[std::string(name) + "_impedance"] = c->impedance;
      summary[std::string(name) + "_travel_time_s"] = c->travel_time;
      summary[std::string(name) + "_top_reflection"] = c->Reflection();
    }
    summary["steps"] = stats.steps;
    summary["events"] = stats.events;
    summary["breakpoints"] = stats.breakpoints;
    summary["history_rejections"] = stats.history_rejections;
    summary["derivative_evaluations"] = stats.derivative_evaluations;
    summary["integration_wall_time_s"] = stats.wall_time_s;
    return summary;
  }

  Model md_;
};

// The pipe's two channels' impedances and travel times; extremes overflow, so they are checked as computed.
struct Pipe {
  double length, area, polar_moment, young, shear, density;
};
Pipe ReadPipe(const JsonReader& r) {
  Pipe p;
  p.length = r.Number("length_m", Range::Positive());
  const double outer = r.Number("outer_diameter_m", Range::Positive());
  const double inner = r.Number("inner_diameter_m", Range::NonNegative());
  if (!(inner < outer)) throw InputError(r.PathOf("inner_diameter_m"), "expected a number below outer_diameter_m");
  p.area = kPi / 4 * (outer * outer - inner * inner);
  p.polar_moment = kPi / 32 * (std::pow(outer, 4) - std::pow(inner, 4));
  p.young = r.Number("youngs_modulus_Pa", Range::Positive());
  p.shear = r.Number("shear_modulus_Pa", Range::Positive());
  p.density = r.Number("density_kg_m3", Range::Positive());
  r.Finish();
  return p;
}

void SetWaves(double section, double modulus, double density, double length, const std::string& path, WaveChannel& c) {
  c.impedance = section * std::sqrt(modulus * density);
  c.travel_time = length / std::sqrt(modulus / density);
  if (!(c.impedance > 0 && std::isfinite(c.impedance) && c.travel_time > 0 && std::isfinite(c.travel_time)))
    throw InputError(path, "impedance " + ReadableNumber(c.impedance) + " and travel time " +
                               ReadableNumber(c.travel_time) + " s must be positive and finite: the pipe's size, "
                               "modulus or density is out of range");
}

// A friction law of the bit's axial speed, smooth (file comment); absent: none.
std::optional<bitrock::FrictionLaw> ReadSmoothLaw(const JsonReader& r, const std::string& key) {
  if (!r.Has(key)) return std::nullopt;
  bitrock::FrictionLaw law = ReadFrictionLaw(r.Raw(key), r.PathOf(key));
  if (law.IsSetValued())
    throw InputError(r.PathOf(key) + "/law", "expected a smooth law (viscous, sqrt_regularized, tanh_hump, rational, "
                                             "squared_sqrt_cutting), got the set-valued " + law.Kind() +
                                             ": this model has no stuck regime");
  return law;
}

// A dissipative top: the dashpot d (> 0), the input's gain g (default `default_gain`, or d if none) and the input.
void ReadTop(const JsonReader& r, const char* damping_key, const char* gain_key, std::optional<double> default_gain,
             const char* input_key, WaveChannel& c) {
  c.top_damping = r.Number(damping_key, Range::Positive());
  c.top_gain = r.Number(gain_key, Range::NonNegative(), default_gain.value_or(c.top_damping));
  c.input = model::Schedule::FromJson(r.Raw(input_key), r.PathOf(input_key));
  r.Finish();
}

class InterconnectedWavesKind : public ModelKind {
 public:
  std::string name() const override { return "interconnected_waves"; }
  std::string description() const override {
    return "the chapter's interconnected axial and torsional waves (sect. 2.5, eqs. 2.12-2.13): one uniform pipe, "
           "dissipative tops under a hook force H(t) and a top speed Omega(t), a bit whose weight F(v) and torque "
           "F~(v) both follow its axial speed v";
  }
  nlohmann::json FieldSchema() const override {
    return {
        {"string/length_m", "L > 0, top to bit"},
        {"string/outer_diameter_m", "> 0"},
        {"string/inner_diameter_m", ">= 0, < outer (Gamma = pi (D^2 - d^2) / 4, Sigma = pi (D^4 - d^4) / 32)"},
        {"string/youngs_modulus_Pa", "E > 0"},
        {"string/shear_modulus_Pa", "G > 0"},
        {"string/density_kg_m3", "rho > 0"},
        {"hoist/alpha1_Ns_per_m", "alpha1 > 0: the top's axial dashpot, E Gamma U_s(0) = alpha1 U_t(0) - alpha2 H"},
        {"hoist/alpha2", "alpha2 >= 0, default 1: the hook force's gain"},
        {"hoist/hook_force_N", "H(t) [N] of eq. 2.12, a number or {\"knots\": [[t, v], ...]}; H > 0 pushes the string "
                               "down (the chapter's top boundary as written; no gravity); 0 before t = 0"},
        {"top/beta1_Nms_per_rad", "beta1 > 0: the top's torsional dashpot, G Sigma Phi_s(0) = beta1 Phi_t(0) - "
                                  "beta2 Omega"},
        {"top/beta2_Nms_per_rad", "beta2 >= 0, default beta1 (then the top is torsional_wave's dissipative top)"},
        {"top/speed_rad_s", "Omega(t) [rad/s], a number or {\"knots\": [[t, v], ...]}; 0 before t = 0"},
        {"bit/mass_kg", "M > 0"},
        {"bit/inertia_kgm2", "J > 0 (the chapter's J = M r^2)"},
        {"bit/weight_law", "F(v): the weight on bit [N] against the bit's axial speed v [m/s], a smooth friction law "
                           "(its torque fields read as forces, its speeds as m/s), resisting; optional, default none "
                           "(the chapter's: rational, p k v / (k^2 v^2 + zeta))"},
        {"bit/torque_law", "F~(v): the torque on bit [N m] against the bit's AXIAL speed v [m/s], a smooth friction "
                           "law, resisting the rotation; optional, default none"},
        {"friction laws", FrictionLawSchema()},
    };
  }

  std::unique_ptr<PreparedModel> Prepare(const JsonReader& r) const override {
    Model md;
    const JsonReader string = r.Object("string");
    const Pipe pipe = ReadPipe(string);
    SetWaves(pipe.area, pipe.young, pipe.density, pipe.length, string.path(), md.axial);
    SetWaves(pipe.polar_moment, pipe.shear, pipe.density, pipe.length, string.path(), md.torsion);
    ReadTop(r.Object("hoist"), "alpha1_Ns_per_m", "alpha2", 1.0, "hook_force_N", md.axial);
    ReadTop(r.Object("top"), "beta1_Nms_per_rad", "beta2_Nms_per_rad", std::nullopt, "speed_rad_s", md.torsion);
    const JsonReader bit = r.Object("bit");
    md.axial.bit_inertia = bit.Number("mass_kg", Range::Positive());
    md.torsion.bit_inertia = bit.Number("inertia_kgm2", Range::Positive());
    md.weight_law = ReadSmoothLaw(bit, "weight_law");
    md.torque_law = ReadSmoothLaw(bit, "torque_law");
    bit.Finish();
    r.Finish();
    return std::make_unique<InterconnectedWavesModel>(std::move(md));
  }
};

}  // namespace

std::unique_ptr<ModelKind> MakeInterconnectedWavesKind() { return std::make_unique<InterconnectedWavesKind>(); }

}  // namespace drillwave::cases
