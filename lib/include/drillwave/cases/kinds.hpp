#pragma once
// Factories of the model kinds; each lives in its own file under lib/src/cases/kinds/.
#include <memory>

#include "drillwave/cases/model_kind.hpp"

namespace drillwave::cases {

std::unique_ptr<ModelKind> MakeTorsionalWaveKind();
std::unique_ptr<ModelKind> MakeTwoMassKind();
std::unique_ptr<ModelKind> MakeLumpedChainKind();
std::unique_ptr<ModelKind> MakeTwoDiscKind();
std::unique_ptr<ModelKind> MakeJeffcottKind();
std::unique_ptr<ModelKind> MakeAxialTorsionalKind();
std::unique_ptr<ModelKind> MakeLumpedAxialTorsionalKind();
std::unique_ptr<ModelKind> MakeInterconnectedWavesKind();

}  // namespace drillwave::cases
