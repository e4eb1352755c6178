#pragma once
// A double for a JSON output: JSON has no NaN or infinity, and a quantity that does not exist (a period of a run that
// never sticks, a correlation of a channel not recorded) is written as null rather than as a made-up number.
#include <cmath>
#include <nlohmann/json.hpp>

namespace drillwave::io {

inline nlohmann::json FiniteOrNull(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace drillwave::io
