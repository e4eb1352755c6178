// Model kind "two_disc": the experimental drill-string set-up of the setup seed (Mihajlović, van Veggel, van de Wouw,
// Nijmeijer; eqs. 1-7). An upper disc J_u driven by a DC motor, torque k_m u_c with the input voltage u_c a schedule,
// with friction T_fu (the asymmetric set-valued law of eqs. 5-6); a steel string of stiffness k_theta; a lower disc
// J_l with the brake friction T_fl (the humped set-valued law of eq. 7):
//   J_u theta_u'' + k_theta (theta_u - theta_l) + T_fu(theta_u') = k_m u_c
//   J_l theta_l'' - k_theta (theta_u - theta_l) + T_fl(theta_l') = 0
// integrated in the state (theta_u - theta_l, theta_u', theta_l') of eq. 4. Each disc sticks and slips on its own:
// two independent stick states, every transition located as an event. Any friction law of the foundation may be
// given to either disc; optional dampers (to ground, across the string) default to 0 as in the seed.
#include <algorithm>
#include <cmath>

#include "drillwave/cases/friction_json.hpp"
#include "drillwave/bitrock/friction.hpp"
#include "drillwave/cases/kinds.hpp"
#include "drillwave/cases/statistics.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/model/schedule.hpp"
#include "lumped_friction_process.hpp"

namespace drillwave::cases {
namespace {

using io::JsonReader;
using Range = io::Range;

// The set-up as a lumped chain of two: 0 the upper disc ("top"), 1 the lower disc ("bit").
class TwoDiscModel : public PreparedModel {
 public:
  explicit TwoDiscModel(lumped::Chain chain) : chain_(std::move(chain)) {}

  RunResult Run(const RunSettings& settings) const override {
    const lumped::ChainRun run = lumped::RunChain(chain_, settings);
    RunResult result = lumped::ChainResult(run, settings);  // top = upper disc, bit = lower disc
    for (Channel c : std::vector<Channel>{{"upper_rad_s", run.speed_rad_s[0]},
                                          {"lower_rad_s", run.speed_rad_s[1]},
                                          {"upper_friction_Nm", run.friction_Nm[0]},
                                          {"top_angle_rad", run.angle_rad[0]},
                                          {"top_stuck", run.stuck[0]}})
      result.channels.push_back(std::move(c));
    result.plot_panels = {{"upper_rad_s", "lower_rad_s"}, {"top_torque_Nm", "bit_torque_Nm"}};

    // The lower disc's statistics are under the common keys; the upper disc's go under "top_...".
    const nlohmann::json upper = ComputeStickSlipStatistics(run.stuck_intervals[0], run.time_s, run.speed_rad_s[0],
                                                            run.angle_rad[0], settings.window_begin_s,
                                                            settings.window_end_s)
                                     .ToJson();
    result.summary["top_stick_slip_period_s"] = upper["stick_slip_period_s"];
    result.summary["top_stick_onsets"] = upper["stick_onsets"];
    result.summary["top_stick_fraction"] = upper["stick_fraction"];
    result.summary["top_speed_max_rad_s"] = upper["bit_speed_max_rad_s"];
    result.summary["top_speed_min_rad_s"] = upper["bit_speed_min_rad_s"];
    result.summary["top_speed_mean_rad_s"] = upper["bit_speed_mean_rad_s"];
    // Peak-to-peak speed of the lower disc in the window: 0 at an equilibrium, > 0 on a limit cycle.
    result.summary["bit_speed_range_rad_s"] =
        result.summary["bit_speed_max_rad_s"].get<double>() - result.summary["bit_speed_min_rad_s"].get<double>();
    return result;
  }

  std::vector<LinearizedOperatingPoint> Linearize() const override { return lumped::LinearizeChain(chain_); }
  std::shared_ptr<const analysis::PiecewiseSmoothField> OrbitField() const override {
    return lumped::ChainOrbitField(chain_);
  }

 private:
  lumped::Chain chain_;
};

std::optional<bitrock::FrictionLaw> ReadFriction(const JsonReader& disc) {
  if (!disc.Has("friction")) return std::nullopt;
  return ReadFrictionLaw(disc.Raw("friction"), disc.PathOf("friction"));
}

class TwoDiscKind : public ModelKind {
 public:
  std::string name() const override { return "two_disc"; }
  std::string description() const override {
    return "two-disc drill-string set-up (setup seed eqs. 1-7): motor-driven upper disc, string k_theta, braked lower "
           "disc, each with its own set-valued friction and stick phases";
  }
  nlohmann::json FieldSchema() const override {
    return {
        {"upper_disc/inertia_kgm2", "J_u > 0"},
        {"upper_disc/motor_constant_Nm_per_V", "k_m > 0"},
        {"upper_disc/input_voltage_V", "u_c: a number or {\"knots\": [[t, v], ...]} [V]"},
        {"upper_disc/friction", "friction law T_fu (seed: asymmetric_coulomb_viscous), optional"},
        {"upper_disc/damping_Nms_per_rad", "extra damper to ground, >= 0, default 0"},
        {"string/stiffness_Nm_per_rad", "k_theta > 0"},
        {"string/damping_Nms_per_rad", "damper across the string, >= 0, default 0"},
        {"lower_disc/inertia_kgm2", "J_l > 0"},
        {"lower_disc/friction", "friction law T_fl (seed: humped), optional"},
        {"lower_disc/damping_Nms_per_rad", "extra damper to ground, >= 0, default 0"},
        {"friction_smoothing_rad_s",
         "0 (default) or >= 1e-6 rad/s; > 0 replaces sign(w) by tanh(w / eps) in both laws (smooth reference, no stick phases)"},
        {"friction laws", FrictionLawSchema()},
    };
  }

  std::unique_ptr<PreparedModel> Prepare(const JsonReader& r) const override {
    lumped::Chain m;
    m.inertias.resize(2);
    m.couplings.resize(1);
    m.drive = lumped::Drive::kTorque;

    const JsonReader upper = r.Object("upper_disc");
    m.inertias[0].inertia_kgm2 = upper.Number("inertia_kgm2", Range::Positive());
    m.torque_gain = upper.Number("motor_constant_Nm_per_V", Range::Positive());
    m.setpoint = model::Schedule::FromJson(upper.Raw("input_voltage_V"), upper.PathOf("input_voltage_V"));
    m.inertias[0].friction = ReadFriction(upper);
    m.inertias[0].damping_Nms_per_rad = upper.Number("damping_Nms_per_rad", Range::NonNegative(), 0.0);
    upper.Finish();

    const JsonReader string = r.Object("string");
    m.couplings[0].stiffness_Nm_per_rad = string.Number("stiffness_Nm_per_rad", Range::Positive());
    m.couplings[0].damping_Nms_per_rad = string.Number("damping_Nms_per_rad", Range::NonNegative(), 0.0);
    string.Finish();

    const JsonReader lower = r.Object("lower_disc");
    m.inertias[1].inertia_kgm2 = lower.Number("inertia_kgm2", Range::Positive());
    m.inertias[1].friction = ReadFriction(lower);
    m.inertias[1].damping_Nms_per_rad = lower.Number("damping_Nms_per_rad", Range::NonNegative(), 0.0);
    lower.Finish();

    m.friction_smoothing_rad_s = lumped::ReadFrictionSmoothing(r);
    r.Finish();
    return std::make_unique<TwoDiscModel>(std::move(m));
  }
};

}  // namespace

std::unique_ptr<ModelKind> MakeTwoDiscKind() { return std::make_unique<TwoDiscKind>(); }

}  // namespace drillwave::cases
