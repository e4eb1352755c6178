// Model kind "two_mass": the two-inertia torsional pendulum of the chapter seed (eqs. 2.1–2.4, Fig. 2.1) in the
// three-state form x = (phi_top - phi_bit, phi_top', phi_bit') of eq. 2.3: top and bit inertias with local
// dampers, a shaft of stiffness k and damping c, the top driven by a prescribed speed, a PI speed controller or a
// torque, the bit by any friction law (set-valued ones with real stick phases), scaled by the weight on bit
// (Psi = H u in eq. 2.2). Work in and dissipation are integrated alongside, so the energy balance can be checked.
#include <cmath>
#include <limits>
#include <optional>

#include "drillwave/bitrock/friction.hpp"
#include "drillwave/cases/kinds.hpp"
#include "drillwave/cases/statistics.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/integration/simulator.hpp"
#include "drillwave/model/schedule.hpp"

namespace drillwave::cases {
namespace {

using io::JsonReader;
using Range = io::Range;

constexpr double kRadPerSecToRpm = 60.0 / (2.0 * M_PI);

enum class TopDrive { kPrescribedSpeed, kPiSpeed, kTorque };

struct TwoMass {
  double j_top, j_bit, k, c, d_top, d_bit;
  TopDrive drive;
  model::Schedule setpoint;  // speed [rad/s] or torque [N·m]
  double kp = 0, ki = 0;
  std::optional<bitrock::FrictionLaw> friction;
  model::Schedule weight_on_bit;  // N; scales the friction relative to nominal_weight
  double nominal_weight = 1;
};

// State: 0 twist, 1 top speed, 2 bit speed, 3 bit angle, 4 PI integral, 5 work in, 6 dissipated.
class TwoMassProcess {
 public:
  using State = std::vector<double>;
  explicit TwoMassProcess(const TwoMass& m) : m_(m) {}
  int Dimension() const { return 7; }
  double MaxStep() const { return std::numeric_limits<double>::infinity(); }
  void BeginStep(double) {}
  double PrepareCommit(const integration::Piece&, double, double) { return 0; }
  void Commit(const integration::Piece&) {}

  double FrictionScale(double t) const { return m_.weight_on_bit.Value(t) / m_.nominal_weight; }
  double ShaftTorque(const State& x, double t) const {
    return m_.k * x[0] + m_.c * (TopSpeed(x, t) - (regime_ == 0 ? 0.0 : x[2]));
  }
  double TopSpeed(const State& x, double t) const {
    return m_.drive == TopDrive::kPrescribedSpeed ? m_.setpoint.Value(t) : x[1];
  }
  double DriveTorque(const State& x, double t) const {
    if (m_.drive == TopDrive::kTorque) return m_.setpoint.Value(t);
    if (m_.drive == TopDrive::kPiSpeed) return m_.kp * (m_.setpoint.Value(t) - x[1]) + m_.ki * x[4];
    // Prescribed speed: the torque that keeps the top on its set-point.
    return m_.j_top * m_.setpoint.Slope(t) + ShaftTorque(x, t) + m_.d_top * m_.setpoint.Value(t);
  }
  double BitFriction(const State& x, double t) const {
    if (!m_.friction) return 0;
    const double s = FrictionScale(t);
    if (regime_ == 0) return DrivingTorqueAtRest(x, t);
    if (!m_.friction->IsSetValued()) return s * m_.friction->SlipTorque(x[2]);
    return s * m_.friction->SlipTorque(regime_ > 0 ? std::max(x[2], 1e-300) : std::min(x[2], -1e-300));
  }
  double DrivingTorqueAtRest(const State& x, double t) const { return m_.k * x[0] + m_.c * TopSpeed(x, t); }

  void Derivatives(const State& x, State& dx, double t) const {
    const double wt = TopSpeed(x, t), wb = regime_ == 0 ? 0.0 : x[2];
    const double shaft = m_.k * x[0] + m_.c * (wt - wb);
    const double drive = DriveTorque(x, t);
    const double friction = BitFriction(x, t);
    dx[0] = wt - wb;
    dx[1] = m_.drive == TopDrive::kPrescribedSpeed ? m_.setpoint.Slope(t)
                                                   : (drive - shaft - m_.d_top * wt) / m_.j_top;
    dx[2] = regime_ == 0 ? 0.0 : (shaft - m_.d_bit * wb - friction) / m_.j_bit;
    dx[3] = wb;
    dx[4] = m_.setpoint.Value(t) - wt;
    dx[5] = drive * wt;
    dx[6] = m_.c * (wt - wb) * (wt - wb) + m_.d_top * wt * wt + m_.d_bit * wb * wb + friction * wb;
  }

  int NumWitnesses() const { return m_.friction && m_.friction->IsSetValued() ? 2 : 0; }
  double Witness(int i, double t, const State& x) const {
    if (regime_ == 0) {
      const double s = FrictionScale(t), drive = DrivingTorqueAtRest(x, t);
      return i == 0 ? s * m_.friction->StaticPositive() - drive : drive + s * m_.friction->StaticNegative();
    }
    return i == 0 ? regime_ * x[2] : 1.0;
  }
  bool OnEvent(int i, double t, State& x) {
    const int before = regime_;
    if (regime_ == 0) {
      regime_ = i == 0 ? 1 : -1;
    } else {
      const double s = FrictionScale(t), drive = DrivingTorqueAtRest(x, t);
      regime_ = drive > s * m_.friction->StaticPositive() ? 1 : (drive < -s * m_.friction->StaticNegative() ? -1 : 0);
    }
    if (regime_ == 0 || before == 0) x[2] = 0;
    if (regime_ == 0 && before != 0) stuck.push_back({t, std::numeric_limits<double>::infinity()});
    if (regime_ != 0 && before == 0 && !stuck.empty()) stuck.back().end_s = t;
    return regime_ != before;
  }
  double NextBreakpoint() const {
    double next = std::numeric_limits<double>::infinity();
    for (const model::Schedule* s : {&m_.setpoint, &m_.weight_on_bit})
      for (const auto& k : s->knots())
        if (k.first > passed_) next = std::min(next, k.first);
    return next;
  }
  void OnBreakpoint(double t) { passed_ = t; }

  int regime_ = 1;
  std::vector<StuckInterval> stuck;

 private:
  const TwoMass& m_;
  double passed_ = -std::numeric_limits<double>::infinity();
};

class TwoMassModel : public PreparedModel {
 public:
  explicit TwoMassModel(TwoMass m) : m_(std::move(m)) {}

  RunResult Run(const RunSettings& settings) const override {
    TwoMassProcess process(m_);
    State x(7, 0.0);
    x[1] = m_.drive == TopDrive::kPrescribedSpeed ? m_.setpoint.Value(0) : 0.0;
    // A set-valued bit at rest starts stuck unless the shaft already overcomes the static friction.
    if (m_.friction && m_.friction->IsSetValued()) {
      process.regime_ = 0;
      process.stuck.push_back({0.0, std::numeric_limits<double>::infinity()});
    }
    RunResult result;
    std::vector<double> top, bit, shaft, tob, angle, stuck_flag, balance;
    auto sample = [&](double t, const State& s) {
      result.time_s.push_back(t);
      top.push_back(process.TopSpeed(s, t) * kRadPerSecToRpm);
      bit.push_back((process.regime_ == 0 ? 0.0 : s[2]) * kRadPerSecToRpm);
      shaft.push_back(process.ShaftTorque(s, t));
      tob.push_back(process.BitFriction(s, t));
      angle.push_back(s[3]);
      stuck_flag.push_back(process.regime_ == 0 ? 1.0 : 0.0);
      const double wt = process.TopSpeed(s, t), wb = process.regime_ == 0 ? 0.0 : s[2];
      const double stored = 0.5 * m_.j_top * wt * wt + 0.5 * m_.j_bit * wb * wb + 0.5 * m_.k * s[0] * s[0];
      balance.push_back(s[5] - s[6] - (stored - initial_energy_));
    };
    const double wt0 = x[1];
    initial_energy_ = 0.5 * m_.j_top * wt0 * wt0;
    sample(0.0, x);
    double next = settings.output_interval_s;
    State xs(7);
    auto observer = [&](const integration::Piece& p) {
      if (settings.output_interval_s <= 0) return sample(p.t1, p.x1);
      while (next <= p.t1 + 1e-12 * std::max(1.0, p.t1)) {
        integration::InterpolatePiece(p, std::min(next, p.t1), xs);
        sample(next, xs);
        next = result.time_s.size() * settings.output_interval_s;
      }
    };
    integration::Simulator<TwoMassProcess> sim(process, settings.integrator);
    sim.Integrate(0.0, x, settings.duration_s, observer);

    result.channels = {{"top_rpm", top},         {"bit_rpm", bit},          {"top_torque_Nm", shaft},
                       {"bit_torque_Nm", tob},   {"bit_angle_rad", angle},  {"bit_stuck", stuck_flag},
                       {"energy_balance_residual_J", balance}};
    result.plot_panels = {{"top_rpm", "bit_rpm"}, {"top_torque_Nm", "bit_torque_Nm"}};
    std::vector<double> bit_rad(bit.size());
    for (std::size_t i = 0; i < bit.size(); ++i) bit_rad[i] = bit[i] / kRadPerSecToRpm;
    result.summary = ComputeStickSlipStatistics(process.stuck, result.time_s, bit_rad, angle, settings.window_begin_s,
                                                settings.window_end_s)
                         .ToJson();
    double worst = 0;
    for (double b : balance) worst = std::max(worst, std::abs(b));
    result.summary["energy_balance_residual_max_J"] = worst;
    result.summary["steps"] = sim.stats().steps;
    result.summary["events"] = sim.stats().events;
    result.summary["derivative_evaluations"] = sim.stats().derivative_evaluations;
    return result;
  }

 private:
  using State = std::vector<double>;
  TwoMass m_;
  mutable double initial_energy_ = 0;
};

class TwoMassKind : public ModelKind {
 public:
  std::string name() const override { return "two_mass"; }
  std::string description() const override {
    return "two-inertia torsional pendulum (chapter eqs. 2.1–2.4): top and bit inertias, shaft k and c, local dampers";
  }
  nlohmann::json FieldSchema() const override {
    return {{"top_inertia_kgm2", "> 0"},
            {"bit_inertia_kgm2", "> 0"},
            {"stiffness_Nm_per_rad", "shaft k > 0"},
            {"shaft_damping_Nms_per_rad", "shaft c >= 0"},
            {"top_damping_Nms_per_rad", ">= 0"},
            {"bit_damping_Nms_per_rad", ">= 0"},
            {"top/type", "prescribed_speed | pi_speed | torque"},
            {"top/speed_rad_s", "set-point schedule (prescribed_speed, pi_speed)"},
            {"top/torque_Nm", "schedule (torque)"},
            {"top/kp_Nms_per_rad", "pi_speed: >= 0"},
            {"top/ki_Nm_per_rad", "pi_speed: >= 0"},
            {"bit/friction", "friction law (see torsional_wave)"},
            {"bit/weight_on_bit_N", "schedule scaling the bit friction relative to nominal_weight_on_bit_N (default: nominal)"},
            {"bit/nominal_weight_on_bit_N", "> 0, the weight the friction law's levels refer to"}};
  }

  std::unique_ptr<PreparedModel> Prepare(const JsonReader& r) const override {
    TwoMass m;
    m.j_top = r.Number("top_inertia_kgm2", Range::Positive());
    m.j_bit = r.Number("bit_inertia_kgm2", Range::Positive());
    m.k = r.Number("stiffness_Nm_per_rad", Range::Positive());
    m.c = r.Number("shaft_damping_Nms_per_rad", Range::NonNegative());
    m.d_top = r.Number("top_damping_Nms_per_rad", Range::NonNegative());
    m.d_bit = r.Number("bit_damping_Nms_per_rad", Range::NonNegative());
    const JsonReader top = r.Object("top");
    const std::string type = top.String("type", {"prescribed_speed", "pi_speed", "torque"});
    if (type == "torque") {
      m.drive = TopDrive::kTorque;
      m.setpoint = model::Schedule::FromJson(top.Raw("torque_Nm"), top.PathOf("torque_Nm"));
    } else {
      m.drive = type == "pi_speed" ? TopDrive::kPiSpeed : TopDrive::kPrescribedSpeed;
      m.setpoint = model::Schedule::FromJson(top.Raw("speed_rad_s"), top.PathOf("speed_rad_s"));
      if (type == "pi_speed") {
        m.kp = top.Number("kp_Nms_per_rad", Range::NonNegative());
        m.ki = top.Number("ki_Nm_per_rad", Range::NonNegative());
      }
    }
    top.Finish();
    const JsonReader bit = r.Object("bit");
    if (bit.Has("friction")) m.friction = bitrock::FrictionLaw::FromJson(bit.Raw("friction"), bit.PathOf("friction"));
    m.nominal_weight = bit.Number("nominal_weight_on_bit_N", Range::Positive(), 1.0);
    m.weight_on_bit = bit.Has("weight_on_bit_N")
                          ? model::Schedule::FromJson(bit.Raw("weight_on_bit_N"), bit.PathOf("weight_on_bit_N"))
                          : model::Schedule(m.nominal_weight);
    for (const auto& [t, w] : m.weight_on_bit.knots())
      if (w < 0) throw InputError(bit.PathOf("weight_on_bit_N"), "expected weights >= 0");
    bit.Finish();
    r.Finish();
    return std::make_unique<TwoMassModel>(std::move(m));
  }
};

}  // namespace

std::unique_ptr<ModelKind> MakeTwoMassKind() { return std::make_unique<TwoMassKind>(); }

}  // namespace drillwave::cases
