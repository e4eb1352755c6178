// Model kind "two_mass": the two-inertia torsional pendulum of the chapter seed (eqs. 2.1–2.4, Fig. 2.1) in the
// three-state form x = (phi_top - phi_bit, phi_top', phi_bit') of eq. 2.3: top and bit inertias with local
// dampers, a shaft of stiffness k and damping c, the top driven by a prescribed speed, a PI speed controller or a
// torque, the bit by any friction law (set-valued ones with real stick phases), scaled by the weight on bit
// (Psi = H u in eq. 2.2). Work in and dissipation are integrated alongside, so the energy balance can be checked.
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
  explicit TwoMassModel(lumped::Chain chain) : chain_(std::move(chain)) {}

  RunResult Run(const RunSettings& settings) const override {
    return lumped::ChainResult(lumped::RunChain(chain_, settings), settings);
  }

  std::vector<LinearizedOperatingPoint> Linearize() const override { return lumped::LinearizeChain(chain_); }
  std::shared_ptr<const analysis::PiecewiseSmoothField> OrbitField() const override {
    return lumped::ChainOrbitField(chain_);
  }

 private:
  lumped::Chain chain_;
};

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
            {"string/stiffness_Nm_per_rad", "shaft k > 0"},
            {"string/damping_Nms_per_rad", "shaft c >= 0, default 0"},
            {"bit/inertia_kgm2", "> 0"},
            {"bit/damping_Nms_per_rad", "local damper at the bit, >= 0, default 0"},
            {"bit/friction", "friction law (see torsional_wave)"},
            {"bit/weight_on_bit_N", "schedule scaling the bit friction relative to nominal_weight_on_bit_N (default: nominal)"},
            {"bit/nominal_weight_on_bit_N", "> 0, the weight the friction law's levels refer to"},
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
    bit.Finish();
    r.Finish();
    return std::make_unique<TwoMassModel>(std::move(m));
  }
};

}  // namespace

std::unique_ptr<ModelKind> MakeTwoMassKind() { return std::make_unique<TwoMassKind>(); }

}  // namespace drillwave::cases
