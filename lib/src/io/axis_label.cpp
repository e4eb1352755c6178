#include "drillwave/io/axis_label.hpp"

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <utility>

namespace drillwave::io {
namespace {

// Unit suffixes of drillwave's channel and field names (the kinds' fields, the recordings' channels), with their
// printed form. Matched on whole "_"-separated parts, longest first, so "Nms_per_rad" wins over "rad".
const std::vector<std::pair<std::string, std::string>>& UnitSuffixes() {
  static const std::vector<std::pair<std::string, std::string>> units = {
      {"Nms_per_rad_m", "N m s/(rad m)"}, {"Nms_per_rad", "N m s/rad"}, {"V_s_per_rad", "V s/rad"},
      {"Nm_per_rad", "N m/rad"}, {"Nm_per_A", "N m/A"}, {"Nm_per_V", "N m/V"}, {"V_per_rad", "V/rad"},
      {"V_per_Hz", "V/Hz"}, {"Ns_per_m2", "N s/m²"}, {"Ns_per_m", "N s/m"}, {"N_per_m", "N/m"},
      {"s_per_rad", "s/rad"}, {"rad_s", "rad/s"}, {"m_s2", "m/s²"}, {"m_s", "m/s"}, {"kg_m3", "kg/m³"},
      {"kgm2", "kg m²"}, {"kNm", "kN m"}, {"Nm", "N m"}, {"kN", "kN"}, {"N", "N"}, {"Pa", "Pa"}, {"V", "V"},
      {"A", "A"}, {"H", "H"}, {"Hz", "Hz"}, {"ohm", "Ω"}, {"kg", "kg"}, {"m", "m"}, {"s", "s"}, {"rad", "rad"},
      {"rpm", "rpm"}};
  return units;
}

// Recording channels' abbreviations, spelt out.
const std::vector<std::pair<std::string, std::string>>& Abbreviations() {
  static const std::vector<std::pair<std::string, std::string>> words = {
      {"tob", "torque on bit"}, {"wob", "weight on bit"}, {"rop", "rate of penetration"}};
  return words;
}

bool IsGreekLetterName(const std::string& word) {
  static const char* const names[] = {"alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta",
                                      "theta", "kappa", "lambda", "mu", "nu", "xi", "rho",
                                      "sigma", "tau", "phi", "chi", "psi", "omega"};
  return std::find(std::begin(names), std::end(names), word) != std::end(names);
}

bool IsIndex(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
}

std::string Replace(std::string text, char from, char to) {
  std::replace(text.begin(), text.end(), from, to);
  return text;
}

// A symbol: a single letter or a Greek letter's name, with subscripts ("T_s", "nu_f", "sigma_l").
bool IsSymbol(const std::string& stem) {
  const std::string first = stem.substr(0, stem.find('_'));
  return first.size() == 1 || IsGreekLetterName(first);
}

// A symbol is printed as written; a stem of words ("top_torque") with spaces.
std::string StemText(const std::string& stem) {
  if (IsSymbol(stem)) return stem;
  for (const auto& [short_form, words] : Abbreviations())
    if (stem == short_form) return words;
  return Replace(stem, '_', ' ');
}

// The stem and unit of a name, "" as the unit when none matches or the match would be a symbol's subscript.
std::pair<std::string, std::string> SplitUnit(const std::string& name) {
  for (const auto& [suffix, unit] : UnitSuffixes()) {
    if (name.size() <= suffix.size() + 1) continue;
    const std::size_t at = name.size() - suffix.size();
    if (name.compare(at, suffix.size(), suffix) != 0 || name[at - 1] != '_') continue;
    const std::string stem = name.substr(0, at - 1);
    // "mu_s", "mu_c": the static friction coefficient, not a mu in seconds.
    if (suffix.size() == 1 && IsGreekLetterName(stem)) continue;
    return {stem, unit};
  }
  return {name, ""};
}

// "sections", "0" -> "section 0": an array element named by its array.
std::string ElementName(const std::string& array, const std::string& index) {
  std::string singular = array;
  if (singular.size() > 1 && singular.back() == 's') singular.pop_back();
  return StemText(singular) + " " + index;
}

// RFC 6901: "~1" is "/", "~0" is "~".
std::vector<std::string> PointerSegments(const std::string& pointer) {
  std::vector<std::string> segments;
  std::size_t at = pointer.empty() || pointer[0] != '/' ? 0 : 1;
  while (at <= pointer.size()) {
    const std::size_t end = std::min(pointer.find('/', at), pointer.size());
    std::string segment;
    for (std::size_t i = at; i < end; ++i) {
      if (pointer[i] == '~' && i + 1 < end && (pointer[i + 1] == '0' || pointer[i + 1] == '1')) {
        segment += pointer[++i] == '1' ? '/' : '~';
      } else {
        segment += pointer[i];
      }
    }
    segments.push_back(segment);
    at = end + 1;
  }
  return segments;
}

// The words for the objects above a field: "bit", "upper disc", "string section 0".
std::string Context(const std::vector<std::string>& segments) {
  std::string text;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    if (i == 0 && segments[i] == "model") continue;  // every parameter is the model's; it says nothing
    if (i + 1 < segments.size() && IsIndex(segments[i + 1])) {
      text += (text.empty() ? "" : " ") + ElementName(segments[i], segments[i + 1]);
      ++i;
    } else {
      text += (text.empty() ? "" : " ") + (IsIndex(segments[i]) ? segments[i] : StemText(segments[i]));
    }
  }
  return text;
}

std::string Joined(const std::string& context, const std::string& name) {
  return context.empty() ? name : context + " " + name;
}

}  // namespace

Quantity QuantityOfName(const std::string& name) {
  const auto [stem, unit] = SplitUnit(name);
  std::string words = StemText(stem);
  // "bit_rpm" is the bit's speed; the unit alone says it, the label should too.
  const bool speed_unit = unit == "rpm" || unit == "rad/s";
  if (speed_unit && !IsSymbol(stem) && words.find("speed") == std::string::npos && words.find("velocity") == std::string::npos)
    words += " speed";
  return {words, unit};
}

Quantity QuantityOfPointer(const std::string& pointer) {
  const std::vector<std::string> segments = PointerSegments(pointer);
  // A schedule's knot: FIELD/knots/i/j, j = 0 its time, j = 1 its value.
  const std::size_t n = segments.size();
  if (n >= 4 && segments[n - 3] == "knots" && IsIndex(segments[n - 2]) && (segments[n - 1] == "0" || segments[n - 1] == "1")) {
    const std::vector<std::string> above(segments.begin(), segments.end() - 4);
    const Quantity field = QuantityOfName(segments[n - 4]);
    const std::string name = Joined(Context(above), field.name);
    if (segments[n - 1] == "0") return {name + ": time of knot " + segments[n - 2], "s"};
    return {name + " at knot " + segments[n - 2], field.unit};
  }
  std::size_t field = n;  // the last segment that is not an array index
  while (field > 0 && IsIndex(segments[field - 1])) --field;
  if (field == 0) return {pointer, ""};
  const Quantity q = QuantityOfName(segments[field - 1]);
  std::string name = Joined(Context({segments.begin(), segments.begin() + static_cast<std::ptrdiff_t>(field - 1)}), q.name);
  for (std::size_t i = field; i < n; ++i) name += " " + segments[i];  // an element of an array field
  return {name, q.unit};
}

std::string AxisLabel(const Quantity& quantity) {
  return quantity.unit.empty() ? quantity.name : quantity.name + " [" + quantity.unit + "]";
}

std::string AxisLabelOfChannels(const std::vector<std::string>& channel_names) {
  std::vector<Quantity> quantities;
  for (const std::string& name : channel_names) quantities.push_back(QuantityOfName(name));
  const bool one_unit = !quantities.empty() && std::all_of(quantities.begin(), quantities.end(), [&](const Quantity& q) {
    return q.unit == quantities.front().unit;
  });
  std::string label;
  for (const Quantity& q : quantities)
    label += (label.empty() ? "" : ", ") + (one_unit ? q.name : AxisLabel(q));
  return one_unit ? AxisLabel(Quantity{label, quantities.front().unit}) : label;
}

}  // namespace drillwave::io
