// The list of model kinds. Adding a kind: write lib/src/cases/kinds/<kind>.cpp, declare its factory in kinds.hpp
// and add it here; the runner, the solvers and the output writers stay as they are.
#include "drillwave/cases/kinds.hpp"
#include "drillwave/core/error.hpp"

namespace drillwave::cases {

const std::vector<std::unique_ptr<ModelKind>>& AllKinds() {
  static const std::vector<std::unique_ptr<ModelKind>> kinds = [] {
    std::vector<std::unique_ptr<ModelKind>> k;
    k.push_back(MakeTorsionalWaveKind());
    k.push_back(MakeTwoMassKind());
    k.push_back(MakeLumpedChainKind());
    k.push_back(MakeTwoDiscKind());
    k.push_back(MakeJeffcottKind());
    k.push_back(MakeAxialTorsionalKind());
    k.push_back(MakeLumpedAxialTorsionalKind());
    k.push_back(MakeInterconnectedWavesKind());
    return k;
  }();
  return kinds;
}

const ModelKind& FindKind(const std::string& name, const std::string& json_path) {
  std::string known;
  for (const auto& kind : AllKinds()) {
    if (kind->name() == name) return *kind;
    known += (known.empty() ? "" : ", ") + kind->name();
  }
  throw InputError(json_path, "unknown model kind \"" + name + "\"; expected one of: " + known);
}

const Channel& RunResult::channel(const std::string& name) const {
  for (const Channel& c : channels)
    if (c.name == name) return c;
  throw std::out_of_range("no channel named " + name);
}

std::vector<LinearizedOperatingPoint> PreparedModel::Linearize() const {
  throw InputError("/model/kind", "this model kind has no linearization for stability analysis");
}

std::shared_ptr<const analysis::PiecewiseSmoothField> PreparedModel::OrbitField() const {
  throw InputError("/model/kind", "this model kind has no autonomous field for periodic orbits (two_disc and "
                                  "two_mass have)");
}

}  // namespace drillwave::cases
