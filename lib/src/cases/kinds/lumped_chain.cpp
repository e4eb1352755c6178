// Model kind "lumped_chain": a torsional chain of any number of lumped inertias between the top and the bit, the
// multi-degree-of-freedom lumped models the chapter seed reviews (sect. 2.2: three- and four-degree-of-freedom chains
// of rotary table, drill pipes, drill collars and bit, eq. 2.5's x' = A x + B u + T_f(x)). The top and the bit are
// two_mass's (chain_readers.hpp); between them `string` gives the inner inertias and the couplings, top to bit:
//   top - k_0 - J_1 - k_1 - ... - J_m - k_m - bit,
// each coupling a spring and a damper, each inner inertia with an optional damper to ground. The integration,
// stick phases, energy balance, linearization and periodic orbits are the shared lumped chain's
// (lumped_friction_process.hpp). Sampled more finely, a uniform pipe's chain converges to the wave string
// (tests/cases/lumped_chain_test.cpp).
#include <string>

#include "chain_readers.hpp"
#include "drillwave/cases/kinds.hpp"
#include "drillwave/core/error.hpp"
#include "lumped_friction_process.hpp"

namespace drillwave::cases {
namespace {

using io::JsonReader;
using Range = io::Range;

class LumpedChainKind : public ModelKind {
 public:
  std::string name() const override { return "lumped_chain"; }
  std::string description() const override {
    return "torsional chain of lumped inertias, top to bit (the chapter's 3- and 4-DOF lumped models, eq. 2.5): "
           "springs and dampers between them, local dampers, the top and bit of two_mass";
  }
  nlohmann::json FieldSchema() const override {
    nlohmann::json schema = lumped::ChainEndsSchema();
    schema["string/inertias_kgm2"] = "the inner inertias J_1..J_m, top to bit, each > 0 (m >= 0)";
    schema["string/stiffnesses_Nm_per_rad"] = "k_0..k_m, m + 1 couplings top to bit, each > 0";
    schema["string/dampings_Nms_per_rad"] = "c_0..c_m, the couplings' dampers, each >= 0, default 0";
    schema["string/local_dampings_Nms_per_rad"] = "the inner inertias' dampers to ground, each >= 0, default 0";
    return schema;
  }

  std::unique_ptr<PreparedModel> Prepare(const JsonReader& r) const override {
    lumped::Chain m;
    m.friction_smoothing_rad_s = lumped::ReadFrictionSmoothing(r);
    const JsonReader s = r.Object("string");
    const std::vector<double> inner = s.NumberArray("inertias_kgm2", Range::Positive());
    const std::size_t couplings = inner.size() + 1;
    constexpr std::size_t kMaxInertias = 2000;  // a chain finer than this is a wave string: use axial_torsional
    if (inner.size() > kMaxInertias)
      throw InputError(s.PathOf("inertias_kgm2"), "expected at most " + std::to_string(kMaxInertias) +
                                                      " inner inertias, got " + std::to_string(inner.size()));
    const std::vector<double> k = s.NumberArray("stiffnesses_Nm_per_rad", Range::Positive());
    if (k.size() != couplings)
      throw InputError(s.PathOf("stiffnesses_Nm_per_rad"), "expected " + std::to_string(couplings) +
                                                               " values (one more than inertias_kgm2 has), got " +
                                                               std::to_string(k.size()));
    auto optional = [&](const char* key, std::size_t n) {
      if (!s.Has(key)) return std::vector<double>(n, 0.0);
      std::vector<double> v = s.NumberArray(key, Range::NonNegative());
      if (v.size() != n)
        throw InputError(s.PathOf(key), "expected " + std::to_string(n) + " values, got " + std::to_string(v.size()));
      return v;
    };
    const std::vector<double> c = optional("dampings_Nms_per_rad", couplings);
    const std::vector<double> local = optional("local_dampings_Nms_per_rad", inner.size());
    s.Finish();
    m.inertias.resize(inner.size() + 2);
    for (std::size_t j = 0; j < inner.size(); ++j)
      m.inertias[j + 1].inertia_kgm2 = inner[j], m.inertias[j + 1].damping_Nms_per_rad = local[j];
    for (std::size_t j = 0; j < couplings; ++j) m.couplings.push_back({k[j], c[j]});
    lumped::ReadChainTop(r.Object("top"), m, m.inertias.front());
    const double nominal = lumped::ReadChainBit(r.Object("bit"), m.inertias.back());
    r.Finish();
    return lumped::MakeChainModel(std::move(m), nominal, name());
  }
};

}  // namespace

std::unique_ptr<ModelKind> MakeLumpedChainKind() { return std::make_unique<LumpedChainKind>(); }

}  // namespace drillwave::cases
