#pragma once
// The RGD bit-rock law's fields in a case (bit and rock blocks), read into bitrock::RgdLaw: the input format stays out
// of the physics. Shared by the kinds whose bit drills (axial_torsional, lumped_axial_torsional).
#include <nlohmann/json.hpp>

#include "drillwave/bitrock/rgd.hpp"
#include "drillwave/io/json_reader.hpp"

namespace drillwave::cases {

// Reads a (bit/radius_m) and n (bit/blades) from the bit block, and the rock block (which it finishes).
void ReadRgdBit(const io::JsonReader& bit, bitrock::RgdLaw& law);
void ReadRgdRock(const io::JsonReader& rock, bitrock::RgdLaw& law);
// The documentation of those fields, for FieldSchema.
nlohmann::json RgdFieldSchema();
// What a linearization about steady drilling says of the heterogeneous rock, for its steady state's description:
// null when the rock is homogeneous.
nlohmann::json LinearizedRock(const bitrock::RgdLaw& law);

}  // namespace drillwave::cases
