#pragma once
// The ends of a lumped chain as the kinds two_mass and lumped_chain read them: the driven top (prescribed speed, PI
// top drive, torque) and the bit (inertia, local damper, friction law scaled by the weight on bit, optional normal
// load).
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

}  // namespace drillwave::cases::lumped
