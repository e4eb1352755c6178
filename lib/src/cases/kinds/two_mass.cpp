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
#include "chain_readers.hpp"
#include "lumped_friction_process.hpp"

namespace drillwave::cases {
namespace {

using io::JsonReader;
using Range = io::Range;

class TwoMassKind : public ModelKind {
 public:
  std::string name() const override { return "two_mass"; }
  std::string description() const override {
    return "two-inertia torsional pendulum (chapter eqs. 2.1–2.4): top and bit inertias, shaft k and c, local dampers";
  }
  nlohmann::json FieldSchema() const override {
    nlohmann::json schema = lumped::ChainEndsSchema();
    schema["string/stiffness_Nm_per_rad"] = "shaft k > 0";
    schema["string/damping_Nms_per_rad"] = "shaft c >= 0, default 0";
    return schema;
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
    lumped::ReadChainTop(r.Object("top"), m, top_inertia);
    const double nominal = lumped::ReadChainBit(r.Object("bit"), bit_inertia);
    r.Finish();
    return lumped::MakeChainModel(std::move(m), nominal, name());  // a chain of two: 0 the top, 1 the bit
  }
};

}  // namespace

std::unique_ptr<ModelKind> MakeTwoMassKind() { return std::make_unique<TwoMassKind>(); }

}  // namespace drillwave::cases
