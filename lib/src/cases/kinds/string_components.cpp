#include "string_components.hpp"

namespace drillwave::cases {

using io::JsonReader;
using Range = io::Range;

// Steel pipe has retardation times of milliseconds; up to 10 s the lumped dashpots stay well conditioned (measured:
// the Saldivar string's roots are right up to 1e5 s, and a spurious real root appears near 1e17 s).
constexpr double kMaxRetardationTime_s = 10;

double ReadKelvinVoigt(const JsonReader& string, const char* key) {
  return string.Number(key, Range::Between(0, kMaxRetardationTime_s), 0.0);
}

std::optional<model::JeffcottBha> ReadUnbalance(const JsonReader& bit) {
  if (!bit.Has("unbalance")) return std::nullopt;
  const JsonReader u = bit.Object("unbalance");
  model::JeffcottBha bha;
  bha.mass = u.Number("lateral_mass_kg", Range::Positive());
  bha.stiffness = u.Number("lateral_stiffness_N_per_m", Range::Positive());
  bha.damping = u.Number("lateral_damping_Ns_per_m", Range::NonNegative());
  bha.unbalance_mass = u.Number("unbalance_mass_kg", Range::NonNegative());
  bha.eccentricity = u.Number("eccentricity_m", Range::NonNegative());
  u.Finish();
  return bha;
}

nlohmann::json StringComponentFields(const std::string& string, const std::string& bit) {
  const std::string u = bit + "/unbalance/";
  return {{string + "/kelvin_voigt_s", "eta in [0, 10] s, default 0: Kelvin-Voigt torsion T += -eta G J dw/ds (a dashpot "
                                       "eta G J / piece length across every piece of the string)"},
          {u + "lateral_mass_kg", "M > 0: BHA lateral (Jeffcott) mass; optional object, absent: no lateral motion"},
          {u + "lateral_stiffness_N_per_m", "k > 0"},
          {u + "lateral_damping_Ns_per_m", "c >= 0"},
          {u + "unbalance_mass_kg", "m >= 0, turning with the bit (adds m e^2 to J_b)"},
          {u + "eccentricity_m", "e >= 0"}};
}

}  // namespace drillwave::cases
