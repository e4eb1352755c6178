// Model kind "lumped_axial_torsional": the two-degree-of-freedom drilling model of Richard, Germay & Detournay
// (chapter seed eq. 2.11):
//   I Phi'' + C (Phi - Phi_top(t)) + c (Phi' - Omega(t)) = -T(t),   Phi_top' = Omega(t) (imposed top speed),
//   M U''   = W0(t) - W(t),
// a torsional spring C (given, or G J / L of a string) between the imposed top rotation and the bit, the bit's
// inertia I and mass M, a constant (or scheduled) weight W0 pushing the bit down, and the bit-rock law of RGD with the
// cut delay t_n (bitrock/rgd.hpp: the same law, regimes and t_n search as the wave kind axial_torsional). The run
// starts in steady drilling (prehistory Phi = Omega t, U = V0 t); disturb it through the inputs.
//
// Linearized about steady drilling (Phi = Omega t - T0 / C, U = V0 t, t_n0 = 2 pi / (n Omega)) with
//   delta t_n = -(phi - phi(t - t_n0)) / Omega,  delta d = n (u - u(t - t_n0)) - (n V0 / Omega) (phi - phi(t - t_n0)),
// and scaled by the torsional frequency w0 = sqrt(C / I) (lambda = s / w0, E = 1 - exp(-lambda tau_n)), the
// characteristic function is (derived in lumped_axial_torsional_stability_test.cpp)
//   [(lambda^2 + 2 xi lambda + 1)(lambda^2 + psi E) - beta E lambda^2] / lambda,
//   psi = n a zeta eps I / (M C),  beta = n T_c0 / (2 pi C),  tau_n = 2 pi w0 / (n Omega),  xi = c / (2 sqrt(C I)),
// with T_c0 = a^2 eps d0 / 2 the steady cutting torque.
#include <algorithm>
#include <cmath>
#include <limits>

#include "drillwave/bitrock/rgd.hpp"
#include "rgd_reader.hpp"
#include "drillwave/cases/kinds.hpp"
#include "drillwave/cases/statistics.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/integration/simulator.hpp"
#include "drillwave/model/schedule.hpp"
#include "drilling_run.hpp"

namespace drillwave::cases {
namespace {

using bitrock::Axial;
using bitrock::Turn;
using integration::Side;
using io::JsonReader;
using Range = io::Range;
constexpr double kInf = std::numeric_limits<double>::infinity();

struct Model {
  bitrock::RgdLaw law;
  double stiffness = 0, damping = 0;  // C, c
  double inertia = 0, mass = 0;       // I, M
  model::Schedule top_speed;          // Omega(t) [rad/s]
  model::Schedule weight;             // W0(t) [N]

  double NaturalFrequency() const { return std::sqrt(stiffness / inertia); }  // w0 = sqrt(C / I)
};

// Steady drilling at top speed omega under weight w0: depth of cut, rate of penetration, torque on bit.
struct Steady {
  double omega, depth, rop, tob;
};
Steady SteadyDrilling(const Model& md, double omega, double wob) {
  const double depth = md.law.SteadyDepth(wob);
  return {omega, depth, depth * omega / (2 * kPi), md.law.SteadyTorque(wob, omega)};  // d = n V0 t_n0
}

// The non-dimensional groups of the linearized model (file comment).
struct Groups {
  double psi, beta, tau_n, xi;
};
Groups NonDimensional(const Model& md, const Steady& s) {
  const bitrock::RgdLaw& l = md.law;
  const double w0 = md.NaturalFrequency();
  return {l.blades * l.CutWeightPerDepth() * md.inertia / (md.mass * md.stiffness),
          l.blades * l.CutTorquePerDepthAt(s.omega) * s.depth / (2 * kPi * md.stiffness),
          2 * kPi * w0 / (l.blades * s.omega),
          md.damping / (2 * std::sqrt(md.stiffness * md.inertia))};
}

// State: 0 bit angle, 1 bit position, 2 top angle, 3 bit speed, 4 bit axial speed.
enum Index { kPhi = 0, kU, kTop, kW, kV, kDim };

class Process {
 public:
  using State = std::vector<double>;
  explicit Process(const Model& md)
      : md_(md),
        steady_(SteadyDrilling(md, md.top_speed.Value(0.0), md.weight.Value(0.0))),
        cut_(md.law.blades, steady_.omega, steady_.rop, md.law.surface_passes, md.law.bottom_roughness) {}

  int Dimension() const { return kDim; }
  // The cut delay is looked up in the committed history: steps below a quarter of t_n0 keep it there while the bit
  // turns up to four times faster than the top.
  double MaxStep() const { return 0.25 * 2 * kPi / (md_.law.blades * steady_.omega); }
  void BeginStep(double t0) { step_start_ = t0; }

  State InitialState() const {
    State x(kDim, 0.0);
    x[kTop] = steady_.tob / md_.stiffness;  // the steady twist
    x[kW] = steady_.omega;
    x[kV] = steady_.rop;
    return x;
  }

  void Derivatives(const State& x, State& dx, double t) const {
    const Side side = t <= step_start_ ? Side::kRight : Side::kLeft;
    const bitrock::RgdForces f = Forces(x, t, side);
    dx[kPhi] = rg_.BitSpeed(x[kW]);
    dx[kU] = rg_.AxiallyHeld() ? 0.0 : x[kV];
    dx[kTop] = md_.top_speed.Evaluate(t, t > step_start_).first;
    dx[kW] = rg_.turn == Turn::kStuck ? 0.0 : (f.drive_torque - f.torque) / md_.inertia;
    dx[kV] = rg_.AxiallyHeld() ? 0.0 : (f.drive_force - f.weight) / md_.mass;
  }

  double PrepareCommit(const integration::Piece& p, double abs_tol, double rel_tol) const {
    // The stored angle and position's cubic Hermite interpolant against their exact midpoint.
    const double h = p.t1 - p.t0;
    double worst = 0;
    for (int i : {kPhi, kU}) {
      const double miss = integration::CubicMidpointMiss(h, p.x0[i], p.x1[i], p.f0[i], p.f1[i], p.x_mid[i]);
      const double scale = abs_tol + rel_tol * std::max(std::abs(p.x0[i]), std::abs(p.x1[i]));
      worst = std::max(worst, std::abs(miss) / scale);
    }
    return worst;
  }
  void Commit(const integration::Piece& p) {
    cut_.Commit(p, kPhi, kU, rg_.contact, rg_.last_contact_change, 1.0);
  }

  int NumWitnesses() const { return bitrock::RgdRegimes::kWitnesses; }
  double Witness(int k, double t, const State& x) const {
    const Side side = Side::kLeft;
    return rg_.Witness(
        k, x[kW], x[kV], md_.law.ContactForceAt(x[kU]), [&] { return Forces(x, t, side); },
        [&] { return DepthOfCut(x, t, side); });
  }
  bool OnEvent(int k, double t, State& x) {
    const Turn turn_before = rg_.turn;
    const bool changed =
        rg_.OnEvent(k, t, x[kW], x[kV], md_.law.ContactForceAt(x[kU]), [&] { return Forces(x, t, Side::kLeft); });
    if (rg_.turn == Turn::kStuck && turn_before != Turn::kStuck) stuck_.push_back({t, kInf});
    if (turn_before == Turn::kStuck && rg_.turn != Turn::kStuck && !stuck_.empty()) stuck_.back().end_s = t;
    return changed;
  }

  double NextBreakpoint() const {
    return std::min(md_.top_speed.NextKnotAfter(passed_), md_.weight.NextKnotAfter(passed_));
  }
  void OnBreakpoint(double t) { passed_ = t; }

  // Outputs at a sampled state.
  struct Sample {
    double bit_speed, top_torque, bit_torque, wob, depth, axial_speed, tn, stuck, off_bottom;
  };
  Sample Sampled(double t, const State& x) const {
    const bitrock::RgdForces f = Forces(x, t, Side::kLeft);
    return {rg_.BitSpeed(x[kW]),
            f.drive_torque,
            rg_.turn == Turn::kStuck ? f.drive_torque : f.torque,
            f.weight,
            rg_.contact ? f.depth : std::min(f.depth, 0.0),
            rg_.AxiallyHeld() ? 0.0 : x[kV],
            f.tn,
            rg_.turn == Turn::kStuck ? 1.0 : 0.0,
            rg_.contact ? 0.0 : 1.0};
  }
  const std::vector<StuckInterval>& stuck_intervals() const { return stuck_; }
  const Steady& steady() const { return steady_; }

 private:
  double DepthOfCut(const State& x, double t, Side side, double* tn = nullptr) const {
    return cut_.DepthOfCut(x[kPhi], x[kU], t, side, rg_.contact, rg_.last_contact_change, tn);
  }
  bitrock::RgdForces Forces(const State& x, double t, Side side) const {
    bitrock::RgdForces f;
    const double w = rg_.BitSpeed(x[kW]);
    const double omega = md_.top_speed.Evaluate(t, t > step_start_ || side == Side::kLeft).first;
    f.drive_torque = md_.stiffness * (x[kTop] - x[kPhi]) + md_.damping * (omega - w);
    f.drive_force = md_.weight.Evaluate(t, t > step_start_ || side == Side::kLeft).first;
    f.depth = DepthOfCut(x, t, side, &f.tn);
    if (!rg_.contact) return f;
    // Cutting only into new rock: not while turning backwards, nor before the bit is back past its furthest angle.
    const bool cutting = rg_.turn != Turn::kBackward && x[kPhi] >= cut_.Furthest(t);
    md_.law.OnBottom(rg_.turn, rg_.axial, w, cutting, x[kU], f);
    return f;
  }

  const Model& md_;
  Steady steady_;
  bitrock::CutProfile cut_;
  bitrock::RgdRegimes rg_;
  double step_start_ = 0, passed_ = 0;
  std::vector<StuckInterval> stuck_;
};

class LumpedAxialTorsionalModel : public PreparedModel {
 public:
  explicit LumpedAxialTorsionalModel(Model md) : md_(std::move(md)) {}

  RunResult Run(const RunSettings& settings) const override {
    Process process(md_);
    std::vector<double> x = process.InitialState();
    DrillingSamples d;
    const double runaway = RunawaySpeed(md_.top_speed);
    auto sample = [&](double t, const std::vector<double>& s) {
      process.BeginStep(t);  // look-ups at t from the committed history (left limits inside the last piece)
      const Process::Sample v = process.Sampled(t, s);
      ThrowIfRunaway(t, v.bit_speed, runaway, s);
      d.time.push_back(t), d.top.push_back(md_.top_speed.Value(t)), d.bit.push_back(v.bit_speed);
      d.top_torque.push_back(v.top_torque), d.bit_torque.push_back(v.bit_torque), d.wob.push_back(v.wob);
      d.depth.push_back(v.depth), d.vbit.push_back(v.axial_speed), d.tn.push_back(v.tn), d.stuck.push_back(v.stuck);
      d.off.push_back(v.off_bottom), d.angle.push_back(s[kPhi]);
    };
    sample(0.0, x);
    integration::Simulator<Process> sim(process, settings.integrator);
    sim.Integrate(0.0, x, settings.duration_s, integration::SampleEvery(settings.output_interval_s, sample));

    RunResult result;
    const Steady& s = process.steady();
    SummarizeDrillingRun(d, {}, process.stuck_intervals(), settings, {s.depth, s.rop, s.tob}, sim.stats(), result);
    const Groups g = NonDimensional(md_, s);
    result.summary["torsional_frequency_rad_s"] = md_.NaturalFrequency();
    result.summary["psi"] = g.psi;
    result.summary["beta"] = g.beta;
    result.summary["scaled_cut_delay"] = g.tau_n;
    result.summary["damping_ratio"] = g.xi;
    return result;
  }

  // Steady drilling at the inputs' final values and the linear delay system of small perturbations about it (file
  // comment). States: bit angle, bit speed, bit axial speed, then the bit position, which enters only through the
  // depth of cut's difference n (u - u(t - t_n0)) (a derivative-only state).
  std::vector<LinearizedOperatingPoint> Linearize() const override {
    const double omega = md_.top_speed.knots().back().second, wob = md_.weight.knots().back().second;
    const bitrock::RgdLaw& law = md_.law;
    if (!(omega > 0) || !(wob > law.ContactForce())) return {};  // no steady drilling
    const Steady s = SteadyDrilling(md_, omega, wob);
    const Groups g = NonDimensional(md_, s);
    enum { kAngle = 0, kSpeed, kAxialSpeed, kPosition, kStates };
    analysis::LinearDelaySystem sys;
    sys.a0 = Eigen::MatrixXd::Zero(kStates, kStates);
    sys.derivative_only_states = 1;
    const double tn0 = 2 * kPi / (law.blades * omega);
    analysis::DelayTerm cut{tn0, Eigen::MatrixXd::Zero(kStates, kStates), {}};
    sys.a0(kAngle, kSpeed) = 1;
    sys.a0(kPosition, kAxialSpeed) = 1;
    sys.a0(kSpeed, kAngle) = -md_.stiffness / md_.inertia;
    sys.a0(kSpeed, kSpeed) = -(md_.damping + law.SteadyTorqueSlope(wob, omega)) / md_.inertia;
    const double per_u = law.blades, per_phi = -law.blades * s.rop / omega;  // d(delta d) / du, / dphi
    for (const auto& [row, k] : {std::pair{int(kSpeed), law.CutTorquePerDepthAt(omega) / md_.inertia},
                                 std::pair{int(kAxialSpeed), law.CutWeightPerDepth() / md_.mass}}) {
      sys.a0(row, kPosition) -= k * per_u, cut.retarded(row, kPosition) += k * per_u;
      sys.a0(row, kAngle) -= k * per_phi, cut.retarded(row, kAngle) += k * per_phi;
    }
    sys.delays.push_back(std::move(cut));
    nlohmann::json point = {{"bit_speed_rad_s", omega},
                            {"weight_on_bit_N", wob},
                            {"depth_of_cut_m", s.depth},
                            {"rop_m_h", 3600 * s.rop},
                            {"bit_torque_Nm", s.tob},
                            {"twist_rad", s.tob / md_.stiffness},
                            {"cut_delay_s", tn0},
                            {"torsional_frequency_rad_s", md_.NaturalFrequency()},
                            {"psi", g.psi},
                            {"beta", g.beta},
                            {"scaled_cut_delay", g.tau_n},
                            {"damping_ratio", g.xi}};
    if (law.strength_heterogeneity.on()) point["rock_strength_heterogeneity"] = LinearizedRock(law);
    return {{std::move(point), {"bit_angle_rad", "bit_speed_rad_s", "bit_axial_speed_m_s", "bit_position_m"},
             std::move(sys)}};
  }

 private:
  Model md_;
};

// C from the string block: a given stiffness, or G J / L of a pipe.
double ReadStiffness(const JsonReader& s) {
  if (s.Has("stiffness_Nm_per_rad") == s.Has("length_m"))
    throw InputError(s.path(), "expected either stiffness_Nm_per_rad or the pipe (length_m, outer_diameter_m, "
                               "inner_diameter_m, shear_modulus_Pa), " +
                                   std::string(s.Has("length_m") ? "not both" : "got neither"));
  if (s.Has("stiffness_Nm_per_rad")) return s.Number("stiffness_Nm_per_rad", Range::Positive());
  const double length = s.Number("length_m", Range::Positive());
  const double outer = s.Number("outer_diameter_m", Range::Positive());
  const double inner = s.Number("inner_diameter_m", Range::NonNegative());
  if (inner >= outer) throw InputError(s.PathOf("inner_diameter_m"), "expected a value below outer_diameter_m");
  const double g = s.Number("shear_modulus_Pa", Range::Positive());
  return g * kPi / 32 * (std::pow(outer, 4) - std::pow(inner, 4)) / length;
}

class LumpedAxialTorsionalKind : public ModelKind {
 public:
  std::string name() const override { return "lumped_axial_torsional"; }
  std::string description() const override {
    return "lumped axial-torsional bit of Richard, Germay & Detournay (chapter eq. 2.11): torsional spring C to an "
           "imposed top speed, bit inertia I and mass M under a weight W0, the RGD bit-rock law with the cut delay "
           "t_n (set-valued contact and friction, lift-off), as in axial_torsional";
  }
  nlohmann::json FieldSchema() const override {
    nlohmann::json fields = {
        {"string/stiffness_Nm_per_rad", "C > 0, torsional spring between top and bit; or the pipe below"},
        {"string/length_m", "> 0: instead of stiffness_Nm_per_rad, C = G J / L of a pipe"},
        {"string/outer_diameter_m", "> 0 (with length_m)"},
        {"string/inner_diameter_m", ">= 0, < outer (with length_m)"},
        {"string/shear_modulus_Pa", "G > 0 (with length_m)"},
        {"string/damping_Nms_per_rad", "c >= 0, default 0: dashpot across the spring, c (Omega - w)"},
        {"top/speed_rad_s", "Omega(t), imposed top speed schedule [rad/s], > 0 at t = 0"},
        {"bit/inertia_kgm2", "I > 0 (bit and BHA)"},
        {"bit/mass_kg", "M > 0"},
        {"hoist/weight_on_bit_N", "W0(t) schedule [N], the constant downward force on the bit (hook load set-point); "
                                  "W0(0) > a sigma l"}};
    fields.update(RgdFieldSchema());
    return fields;
  }

  std::unique_ptr<PreparedModel> Prepare(const JsonReader& r) const override {
    Model md;
    const JsonReader s = r.Object("string");
    md.stiffness = ReadStiffness(s);
    md.damping = s.Number("damping_Nms_per_rad", Range::NonNegative(), 0.0);
    s.Finish();
    const JsonReader td = r.Object("top");
    md.top_speed = model::Schedule::FromJson(td.Raw("speed_rad_s"), td.PathOf("speed_rad_s"));
    td.Finish();
    if (!(md.top_speed.Value(0.0) > 0))
      throw InputError(td.PathOf("speed_rad_s"), "the run starts in steady drilling: the speed at t = 0 must be > 0");
    const JsonReader b = r.Object("bit");
    md.inertia = b.Number("inertia_kgm2", Range::Positive());
    md.mass = b.Number("mass_kg", Range::Positive());
    ReadRgdBit(b, md.law);
    b.Finish();
    ReadRgdRock(r.Object("rock"), md.law);
    const JsonReader h = r.Object("hoist");
    md.weight = model::Schedule::FromJson(h.Raw("weight_on_bit_N"), h.PathOf("weight_on_bit_N"));
    h.Finish();
    r.Finish();
    if (!(md.weight.Value(0.0) > md.law.ContactForce()))
      throw InputError(h.PathOf("weight_on_bit_N"),
                       "expected more than the wear-flat contact force a sigma l = " +
                           ReadableNumber(md.law.ContactForce()) + " N at t = 0 (no cutting otherwise; a = "
                           "/model/bit/radius_m, sigma l = /model/rock/sigma_l_N_per_m)");
    return std::make_unique<LumpedAxialTorsionalModel>(std::move(md));
  }
};

}  // namespace

std::unique_ptr<ModelKind> MakeLumpedAxialTorsionalKind() { return std::make_unique<LumpedAxialTorsionalKind>(); }

}  // namespace drillwave::cases
