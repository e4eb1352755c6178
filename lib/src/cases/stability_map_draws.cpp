// Stability maps over parameter draws (a posterior's samples): the probability of stick-slip per grid point.
#include <algorithm>
#include <cmath>
#include <limits>

#include "drillwave/cases/stability_map.hpp"
#include "drillwave/cases/case_runner.hpp"
#include "drillwave/cases/sweep.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/io/csv.hpp"
#include "drillwave/io/json_reader.hpp"

namespace drillwave::cases {

ParameterDraws ReadParameterDraws(const std::string& file, const nlohmann::json& document, int count) {
  if (count < 0 || count > 100000)
    throw ParameterError("draw_count", "expected a whole number in [0, 100000] (0: every row), got " +
                                         std::to_string(count));
  io::CsvTable table;
  try {
    table = io::ReadCsv(file);
  } catch (const InputError& e) {
    throw ParameterError("draws", e.what());
  }
  ParameterDraws draws;
  std::vector<std::size_t> columns;
  for (std::size_t j = 0; j < table.header.size(); ++j) {
    const std::string& name = table.header[j];
    if (name.empty() || name[0] != '/') continue;
    nlohmann::json::json_pointer ptr;
    try {
      ptr = nlohmann::json::json_pointer(name);
    } catch (const nlohmann::json::exception&) {
      throw ParameterError("draws", file + ": column " + name + " is not a JSON pointer");
    }
    if (!document.contains(ptr) || !document.at(ptr).is_number())
      throw ParameterError("draws", file + ": column " + name + " is no number in the case");
    draws.pointers.push_back(name);
    columns.push_back(j);
  }
  if (columns.empty())
    throw ParameterError("draws", file + " has no column named by a JSON pointer (e.g. /model/bit/friction/mu), as "
                                       "calibrate's posterior_samples.csv has");
  const std::size_t rows = table.columns.empty() ? 0 : table.columns.front().size();
  if (rows == 0) throw ParameterError("draws", file + " has no rows");
  const std::size_t n = count == 0 ? rows : std::min<std::size_t>(rows, static_cast<std::size_t>(count));
  for (std::size_t d = 0; d < n; ++d) {
    const std::size_t row = d * rows / n;  // spread evenly: successive rows of a chain are correlated
    std::vector<double> values;
    for (std::size_t j : columns) {
      const double v = table.columns[j][row];
      if (!std::isfinite(v))
        throw ParameterError("draws", file + ": row " + std::to_string(row + 2) + " of column " + table.header[j] +
                                        " is not a finite number");
      values.push_back(v);
    }
    draws.rows.push_back(std::move(values));
  }
  return draws;
}

StabilityMapResult StabilityMapOverDraws(const nlohmann::json& document, const StabilityMapSpec& spec,
                                         const ParameterDraws& draws, const std::function<void(int, int)>& progress) {
  if (draws.rows.empty()) throw ParameterError("draws", "no draws to map over");
  const double points = static_cast<double>(spec.x.values.size() * spec.y.values.size());
  CheckPointsWork(ParseCase(document), points * static_cast<double>(draws.rows.size() + 1), spec.simulate, "draws");
  StabilityMapResult result = StabilityMap2D(document, spec);
  const std::size_t cells = result.cells.size();
  std::vector<int> unstable(cells, 0), stick_slip(cells, 0), simulated(cells, 0);
  const int n = static_cast<int>(draws.rows.size());
  for (int d = 0; d < n; ++d) {
    nlohmann::json doc = document;
    for (std::size_t i = 0; i < draws.pointers.size(); ++i) io::SetByPointer(doc, draws.pointers[i], draws.rows[d][i]);
    const StabilityMapResult drawn = StabilityMap2D(doc, spec);
    result.linear_wall_time_s += drawn.linear_wall_time_s;
    result.simulation_wall_time_s += drawn.simulation_wall_time_s;
    result.full_spectra += drawn.full_spectra;
    for (std::size_t k = 0; k < cells; ++k) {
      const StabilityMapCell& c = drawn.cells[k];
      unstable[k] += c.analysed && !LinearlySteady(c) ? 1 : 0;
      if (c.regime == Regime::kNotSimulated || c.regime == Regime::kFailed) continue;
      ++simulated[k];
      stick_slip[k] += c.regime == Regime::kStickSlip ? 1 : 0;
    }
    if (progress) progress(d + 1, n);
  }
  result.draws = n;
  result.draw_pointers = draws.pointers;
  for (std::size_t k = 0; k < cells; ++k) {
    result.p_linearly_unstable.push_back(result.cells[k].analysed ? static_cast<double>(unstable[k]) / n
                                                                  : std::numeric_limits<double>::quiet_NaN());
    result.p_stick_slip.push_back(simulated[k] > 0 ? static_cast<double>(stick_slip[k]) / simulated[k]
                                                   : std::numeric_limits<double>::quiet_NaN());
  }
  return result;
}

}  // namespace drillwave::cases
