#include "drillwave/model/schedule.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "drillwave/core/error.hpp"

namespace drillwave::model {

Schedule::Schedule(double constant) : knots_{{0.0, constant}} {}

Schedule::Schedule(std::vector<std::pair<double, double>> knots) : knots_(std::move(knots)) {
  if (knots_.empty()) throw std::invalid_argument("Schedule: needs at least one knot");
  for (std::size_t i = 1; i < knots_.size(); ++i)
    if (knots_[i].first < knots_[i - 1].first) throw std::invalid_argument("Schedule: knot times must not decrease");
}

std::pair<double, double> Schedule::Evaluate(double t, bool left_limit) const {
  // First knot strictly after t (right limit) or at/after t (left limit).
  auto it = left_limit
                ? std::lower_bound(knots_.begin(), knots_.end(), t, [](const auto& k, double v) { return k.first < v; })
                : std::upper_bound(knots_.begin(), knots_.end(), t, [](double v, const auto& k) { return v < k.first; });
  if (it == knots_.begin()) return {knots_.front().second, 0.0};
  if (it == knots_.end()) return {knots_.back().second, 0.0};
  const auto& a = *(it - 1);
  const auto& b = *it;
  if (b.first == a.first) return {left_limit ? a.second : b.second, 0.0};
  const double slope = (b.second - a.second) / (b.first - a.first);
  return {a.second + slope * (t - a.first), slope};
}

Schedule Schedule::FromJson(const nlohmann::json& j, const std::string& json_path) {
  if (j.is_number()) {
    const double v = j.get<double>();
    if (!std::isfinite(v)) throw InputError(json_path, "expected a finite number, got " + ReadableText(j.dump()));
    return Schedule(v);
  }
  if (!j.is_object())
    throw InputError(json_path, "expected a number or {\"knots\": [[t, value], ...]}, got " + std::string(j.type_name()));
  for (const auto& item : j.items())
    if (item.key() != "knots") throw InputError(json_path + "/" + item.key(), "unknown field; expected one of: knots");
  if (!j.contains("knots")) throw InputError(json_path + "/knots", "missing required field (a list of [t, value])");
  const auto& k = j.at("knots");
  const std::string kpath = json_path + "/knots";
  if (!k.is_array() || k.empty()) throw InputError(kpath, "expected a non-empty list of [t, value] pairs");
  std::vector<std::pair<double, double>> knots;
  for (std::size_t i = 0; i < k.size(); ++i) {
    const std::string path = kpath + "/" + std::to_string(i);
    const auto& e = k[i];
    if (!e.is_array() || e.size() != 2 || !e[0].is_number() || !e[1].is_number())
      throw InputError(path, "expected a pair [t_s, value] of numbers, got " + ReadableText(e.dump()));
    const double t = e[0].get<double>(), v = e[1].get<double>();
    if (!std::isfinite(t) || !std::isfinite(v))
      throw InputError(path, "expected finite numbers, got " + ReadableText(e.dump()));
    if (!knots.empty() && t < knots.back().first)
      throw InputError(path + "/0", "knot times must not decrease (" + ReadableNumber(t) + " s after " +
                                        ReadableNumber(knots.back().first) + " s)");
    // Knots closer than the integrator can step (1e-300 s apart crashed a run) are a jump written wrongly.
    if (!knots.empty() && t != knots.back().first && t - knots.back().first < 1e-9 * std::max(1.0, std::abs(t)))
      throw InputError(path + "/0", "knot time " + ReadableNumber(t) + " s is within 1e-9 s of the previous knot's " +
                                        ReadableNumber(knots.back().first) + " s; give both the same time for a jump");
    knots.emplace_back(t, v);
  }
  return Schedule(std::move(knots));
}

nlohmann::json Schedule::ToJson() const {
  if (IsConstant()) return knots_.front().second;
  nlohmann::json k = nlohmann::json::array();
  for (const auto& [t, v] : knots_) k.push_back({t, v});
  return {{"knots", k}};
}

double Schedule::NextKnotAfter(double t) const {
  const auto it = std::upper_bound(knots_.begin(), knots_.end(), t,
                                   [](double time, const std::pair<double, double>& knot) { return time < knot.first; });
  return it == knots_.end() ? std::numeric_limits<double>::infinity() : it->first;
}

}  // namespace drillwave::model
