#pragma once
// Readers of the string and BHA components that more than one kind offers: Kelvin-Voigt damping of the string
// (chapter eq. 2.20) and the BHA's mass unbalance (the Jeffcott rotor at the bit, failure seed eqs. 21-23), with
// their field documentation for `drillwave kinds`.
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "drillwave/io/json_reader.hpp"
#include "drillwave/model/jeffcott_bha.hpp"

namespace drillwave::cases {

// string/kelvin_voigt_s: the retardation time eta in [0, 10] s of T += -eta G J dw/ds, default 0 (none); `key`
// names the axial one (N += eta_a E A dv/ds) likewise.
double ReadKelvinVoigt(const io::JsonReader& string, const char* key = "kelvin_voigt_s");
// bit/unbalance (absent: no lateral motion).
std::optional<model::JeffcottBha> ReadUnbalance(const io::JsonReader& bit);
// Field documentation of both, keyed by their paths below the string and bit blocks (e.g. "string", "bit").
nlohmann::json StringComponentFields(const std::string& string, const std::string& bit);

}  // namespace drillwave::cases
