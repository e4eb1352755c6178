#pragma once
// What the kinds two_mass and lumped_chain share: the ends of the chain as they read them — the driven top
// (prescribed speed, PI top drive, torque) and the bit (inertia, local damper, friction law scaled by the weight on
// bit, optional normal load) — and the prepared model that runs, linearizes and continues the chain.
#include <memory>
#include <string>

#include "drillwave/cases/model_kind.hpp"
#include "drillwave/io/json_reader.hpp"
#include "lumped_friction_process.hpp"

namespace drillwave::cases::lumped {

// Reads /model/top into the chain's drive and its first inertia (`top`); finishes the reader.
void ReadChainTop(const io::JsonReader& top, Chain& chain, Inertia& top_inertia);

// Reads /model/bit into the last inertia; finishes the reader. Returns the nominal weight on bit [N] the friction
// law's levels refer to (1 where the case gives none).
double ReadChainBit(const io::JsonReader& bit, Inertia& bit_inertia);

// The fields ReadChainTop and ReadChainBit read, for a kind's FieldSchema.
nlohmann::json ChainEndsSchema();

// The chain as a prepared model of kind `kind`: the chain's channels (ChainResult), each inner inertia's speed
// (inertia_<j>_rpm; at most six drawn), and with a normal load its channel normal_load_N (the scale times
// `nominal_weight_N`); stability and orbits refuse a normal load (it is a state they do not carry).
std::unique_ptr<PreparedModel> MakeChainModel(Chain chain, double nominal_weight_N, std::string kind);

}  // namespace drillwave::cases::lumped
