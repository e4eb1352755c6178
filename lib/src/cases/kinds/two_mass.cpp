// Model kind "two_mass": the two-inertia torsional pendulum of the chapter seed (eqs. 2.1–2.4, Fig. 2.1) in the
// three-state form x = (phi_top - phi_bit, phi_top', phi_bit') of eq. 2.3: top and bit inertias with local
// dampers, a shaft of stiffness k and damping c, the top driven by a prescribed speed, a PI speed controller or a
// torque, the bit by any friction law (set-valued ones with real stick phases), scaled by the weight on bit
// (Psi = H u in eq. 2.2) or by a simulated normal load that follows the torque on bit (the UFRJ rig, issue 32), the
// PI drive's torque optionally limited. Work in and dissipation are integrated alongside, so the energy balance can be
// checked.
// The integration is the shared lumped chain (lumped_friction_process.hpp), a chain of two here.
#include <algorithm>
#include <cmath>

#include "drillwave/bitrock/friction.hpp"
#include "drillwave/cases/kinds.hpp"
#include "drillwave/cases/statistics.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/model/schedule.hpp"
#include "lumped_friction_process.hpp"
#include "top_components.hpp"

namespace drillwave::cases {
namespace {

using io::JsonReader;
using Range = io::Range;

// The pendulum as a lumped chain of two: 0 the top, 1 the bit.
class TwoMassModel : public PreparedModel {
 public:
  TwoMassModel(lumped::Chain chain, double nominal_weight_N)
      : chain_(std::move(chain)), nominal_weight_N_(nominal_weight_N) {}

  RunResult Run(const RunSettings& settings) const override {
    const lumped::ChainRun run = lumped::RunChain(chain_, settings);
    RunResult result = lumped::ChainResult(run, settings);
    // The simulated normal load in newtons, named apart from a recording's wob_N so that diagnose compares the two only
    // where a --map asks it to.
    if (chain_.HasNormalLoad()) {
      std::vector<double> load = run.friction_scale[1];
      for (double& w : load) w *= nominal_weight_N_;
      result.channels.push_back({"normal_load_N", std::move(load)});
      result.plot_panels.push_back({"normal_load_N"});
    }
    return result;
  }

  std::vector<LinearizedOperatingPoint> Linearize() const override {
    RefuseNormalLoad();
    return lumped::LinearizeChain(chain_);
  }
  std::shared_ptr<const analysis::PiecewiseSmoothField> OrbitField() const override {
    RefuseNormalLoad();
    return lumped::ChainOrbitField(chain_);
  }

 private:
  // The load is a state of its own that the linearization and the orbit field do not carry (yet).
  void RefuseNormalLoad() const {
    if (chain_.HasNormalLoad())
      throw InputError("/model/bit/normal_load", "stability and periodic orbits of two_mass do not include the "
                                                 "simulated normal load yet: remove it to analyse the case");
  }

  lumped::Chain chain_;
  double nominal_weight_N_;
};

// bit/normal_load: the friction's scale as a simulated normal load W that follows the torque on bit T,
// time_constant W' = W_applied(t) + gain (T - reference) - W (lumped::NormalLoad), in the scale of the nominal weight.
lumped::NormalLoad ReadNormalLoad(const JsonReader& load, double nominal_N, const bitrock::FrictionLaw& law) {
  lumped::NormalLoad n;
  const double gain_N_per_Nm = load.Number("torque_gain_N_per_Nm", Range::NonNegative());
  // Above nominal / T_s the load and the torque it makes raise each other without bound.
  const double runaway = nominal_N / law.StaticPositive();
  if (!(gain_N_per_Nm < runaway))
    throw InputError(load.PathOf("torque_gain_N_per_Nm"),
                     "expected a gain below nominal_weight_on_bit_N / the friction's static level = " +
                         ReadableNumber(runaway) + " N per N m (beyond it the load and the torque it makes grow "
                         "without bound), got " + ReadableNumber(gain_N_per_Nm));
  n.gain_per_Nm = gain_N_per_Nm / nominal_N;
  n.reference_Nm = load.Number("reference_torque_Nm", Range::NonNegative(), 0.0);
  n.time_constant_s = load.Number("time_constant_s", Range::Positive());
  load.Finish();
  return n;
}

class TwoMassKind : public ModelKind {
 public:
  std::string name() const override { return "two_mass"; }
  std::string description() const override {
    return "two-inertia torsional pendulum (chapter eqs. 2.1–2.4): top and bit inertias, shaft k and c, local dampers";
  }
  nlohmann::json FieldSchema() const override {
    return {{"top/inertia_kgm2", "> 0"},
            {"top/damping_Nms_per_rad", "local damper at the top, >= 0, default 0"},
            {"top/type", "prescribed_speed | top_drive (PI speed controller) | torque"},
            {"top/speed_rad_s", "set-point schedule (prescribed_speed, top_drive)"},
            {"top/torque_Nm", "schedule (torque)"},
            {"top/kp_Nms_per_rad", "top_drive: >= 0"},
            {"top/ki_Nm_per_rad", "top_drive: >= 0"},
            {"top/torque_limit_Nm",
             "top_drive: >= 0, default 0 (none); the drive's torque clamped to +-limit, its integral held meanwhile"},
            {"string/stiffness_Nm_per_rad", "shaft k > 0"},
            {"string/damping_Nms_per_rad", "shaft c >= 0, default 0"},
            {"bit/inertia_kgm2", "> 0"},
            {"bit/damping_Nms_per_rad", "local damper at the bit, >= 0, default 0"},
            {"bit/friction", "friction law (see torsional_wave)"},
            {"bit/weight_on_bit_N", "schedule scaling the bit friction relative to nominal_weight_on_bit_N (default: nominal)"},
            {"bit/nominal_weight_on_bit_N", "> 0, the weight the friction law's levels refer to"},
            {"bit/normal_load/torque_gain_N_per_Nm",
             "a simulated normal load W following the torque on bit T, the friction scaled by W / nominal: >= 0 and "
             "below nominal / the law's static level"},
            {"bit/normal_load/reference_torque_Nm", ">= 0, default 0: W = weight_on_bit_N + gain (T - reference)"},
            {"bit/normal_load/time_constant_s", "> 0, the lag of W behind its target"},
            {"friction_smoothing_rad_s",
             "0 (default) or >= 1e-6 rad/s; > 0 replaces sign(w) by tanh(w / eps) in the bit law (smooth reference, no stick phases)"}};
  }

  std::unique_ptr<PreparedModel> Prepare(const JsonReader& r) const override {
    lumped::Chain m;
    m.inertias.resize(2);
    m.couplings.resize(1);
    lumped::Inertia& top_inertia = m.inertias[0];
    lumped::Inertia& bit_inertia = m.inertias[1];
    // Fields of the first two_mass cases, named like every other kind's since.
    r.RefuseRenamed("top_inertia_kgm2", "/model/top/inertia_kgm2");
    r.RefuseRenamed("top_damping_Nms_per_rad", "/model/top/damping_Nms_per_rad");
    r.RefuseRenamed("bit_inertia_kgm2", "/model/bit/inertia_kgm2");
    r.RefuseRenamed("bit_damping_Nms_per_rad", "/model/bit/damping_Nms_per_rad");
    r.RefuseRenamed("stiffness_Nm_per_rad", "/model/string/stiffness_Nm_per_rad");
    r.RefuseRenamed("shaft_damping_Nms_per_rad", "/model/string/damping_Nms_per_rad");
    m.friction_smoothing_rad_s = lumped::ReadFrictionSmoothing(r);
    const JsonReader shaft = r.Object("string");
    m.couplings[0].stiffness_Nm_per_rad = shaft.Number("stiffness_Nm_per_rad", Range::Positive());
    m.couplings[0].damping_Nms_per_rad = shaft.Number("damping_Nms_per_rad", Range::NonNegative(), 0.0);
    shaft.Finish();
    const JsonReader top = r.Object("top");
    top_inertia.inertia_kgm2 = top.Number("inertia_kgm2", Range::Positive());
    top_inertia.damping_Nms_per_rad = top.Number("damping_Nms_per_rad", Range::NonNegative(), 0.0);
    if (top.Has("type") && top.Raw("type") == "pi_speed")
      throw InputError(top.PathOf("type"), "the PI speed controller is called \"top_drive\" (as in every kind)");
    const std::string type = top.String("type", {"prescribed_speed", "top_drive", "torque"});
    if (type == "torque") {
      m.drive = lumped::Drive::kTorque;
      m.setpoint = model::Schedule::FromJson(top.Raw("torque_Nm"), top.PathOf("torque_Nm"));
    } else {
      m.drive = type == "top_drive" ? lumped::Drive::kPiSpeed : lumped::Drive::kPrescribedSpeed;
      m.setpoint = model::Schedule::FromJson(top.Raw("speed_rad_s"), top.PathOf("speed_rad_s"));
      if (type == "top_drive") {
        m.pi = ReadPiController(top);
        m.drive_torque_limit_Nm = top.Number("torque_limit_Nm", Range::NonNegative(), 0.0);
      }
    }
    top.Finish();
    const JsonReader bit = r.Object("bit");
    bit_inertia.inertia_kgm2 = bit.Number("inertia_kgm2", Range::Positive());
    bit_inertia.damping_Nms_per_rad = bit.Number("damping_Nms_per_rad", Range::NonNegative(), 0.0);
    if (bit.Has("friction"))
      bit_inertia.friction = bitrock::FrictionLaw::FromJson(bit.Raw("friction"), bit.PathOf("friction"));
    const double nominal = bit.Number("nominal_weight_on_bit_N", Range::Positive(), 1.0);
    const model::Schedule weight = bit.Has("weight_on_bit_N")
                                       ? model::Schedule::FromJson(bit.Raw("weight_on_bit_N"), bit.PathOf("weight_on_bit_N"))
                                       : model::Schedule(nominal);
    std::vector<std::pair<double, double>> scale;
    for (const auto& [t, w] : weight.knots()) {
      if (w < 0) throw InputError(bit.PathOf("weight_on_bit_N"), "expected weights >= 0");
      scale.emplace_back(t, w / nominal);
    }
    bit_inertia.friction_scale = model::Schedule(scale);
    if (bit.Has("normal_load")) {
      if (!bit_inertia.friction)
        throw InputError(bit.PathOf("normal_load"), "a normal load needs bit/friction to scale");
      bit_inertia.normal_load = ReadNormalLoad(bit.Object("normal_load"), nominal, *bit_inertia.friction);
    }
    bit.Finish();
    r.Finish();
    return std::make_unique<TwoMassModel>(std::move(m), nominal);
  }
};

}  // namespace

std::unique_ptr<ModelKind> MakeTwoMassKind() { return std::make_unique<TwoMassKind>(); }

}  // namespace drillwave::cases
