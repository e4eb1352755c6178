#include "drillwave/cases/sweep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/core/parallel.hpp"
#include "drillwave/core/stopwatch.hpp"
#include "drillwave/io/csv.hpp"
#include "drillwave/io/json_reader.hpp"
#include "drillwave/io/output_dir.hpp"
#include "drillwave/io/axis_label.hpp"
#include "drillwave/io/svg_plot.hpp"

namespace drillwave::cases {

double ParseNumber(const std::string& text, const std::string& what) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v))
    throw ParameterError(what, "'" + text + "' is not a finite number");
  return v;
}

namespace {

std::vector<std::string> Split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(text);
  while (std::getline(in, part, separator)) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.emplace_back();
  return parts;
}

// The document with the swept parameter set to v.
nlohmann::json Variant(const nlohmann::json& document, const std::string& pointer, double v) {
  nlohmann::json doc = document;
  io::SetByPointer(doc, pointer, v);
  return doc;
}

}  // namespace

std::vector<double> ParseSweepValues(const std::string& text, const std::string& what) {
  std::vector<double> values;
  if (text.find(':') != std::string::npos) {
    const auto parts = Split(text, ':');
    if (parts.size() != 3) throw ParameterError(what, "'" + text + "': expected first:last:count or v1,v2,...");
    const double first = ParseNumber(parts[0], what), last = ParseNumber(parts[1], what);
    const double count = ParseNumber(parts[2], what);
    if (count < 1 || count != std::floor(count) || count > 1e6)
      throw ParameterError(what, "'" + text + "': the count must be a whole number in [1, 1e6]");
    const int n = static_cast<int>(count);
    for (int i = 0; i < n; ++i) values.push_back(n == 1 ? first : first + (last - first) * i / (n - 1));
  } else {
    for (const std::string& part : Split(text, ',')) values.push_back(ParseNumber(part, what));
  }
  if (values.empty()) throw ParameterError(what, "no values given");
  return values;
}

namespace {
// A run's output samples or its fewest integration steps, whichever are more.
double RunWork(const RunSettings& s) {
  double work = s.output_interval_s > 0 ? s.duration_s / s.output_interval_s : 0;
  if (std::isfinite(s.integrator.max_step)) work = std::max(work, s.duration_s / s.integrator.max_step);
  return work;
}
}  // namespace

void CheckPointsWork(const Case& first, double points, bool runs_each, const std::string& option) {
  const double per_point = kSweepRunMinimumWork + (runs_each ? RunWork(first.settings) : 0.0);
  const double work = points * per_point, limit = kSweepWorkPerMaxSample * MaxSamples();
  if (work > limit)
    throw ParameterError(option, ReadableNumber(points) + " points of about " + ReadableNumber(std::round(per_point)) +
                                 " work units each (" + ReadableNumber(kSweepRunMinimumWork) + " for its analysis" +
                                 (runs_each ? std::string(", the rest its run's output samples or steps") : "") +
                                 ": " + ReadableNumber(work) + " in all) are above the limit of " +
                                 ReadableNumber(limit) + " (" + ReadableNumber(kSweepWorkPerMaxSample) +
                                 " x max_samples); ask for fewer points, or raise max_samples",
                         {"max_samples"});
}

void CheckSweepWork(const Case& first, std::size_t runs) {
  const double per_run = RunWork(first.settings);
  const double work = static_cast<double>(runs) * std::max(per_run, kSweepRunMinimumWork);
  const double limit = kSweepWorkPerMaxSample * MaxSamples();
  if (work > limit)
    throw ParameterError("values", std::to_string(runs) + " runs of about " + ReadableNumber(std::round(per_run)) +
                                     " output samples or steps each (each run counted as at least " +
                                     ReadableNumber(kSweepRunMinimumWork) + ": " + ReadableNumber(work) +
                                     " in all) are above a sweep's limit of " + ReadableNumber(limit) + " (" +
                                     ReadableNumber(kSweepWorkPerMaxSample) + " x max_samples); sweep fewer "
                                     "values, or raise max_samples",
                         {"max_samples"});
}

SweepResult RunSweep(const nlohmann::json& document, const SweepSpec& spec, const SweepProgress& progress) {
  if (spec.values.empty()) throw ParameterError("values", "no values to sweep");
  if (spec.jobs < 1) throw ParameterError("jobs", std::to_string(spec.jobs) + " is not >= 1");
  auto parse = [&](double v) {
    if (!std::isfinite(v)) throw InputError(spec.pointer, "a sweep value is not finite");
    try {
      return ParseCase(Variant(document, spec.pointer, v));
    } catch (const InputError& e) {
      throw InputError(e.json_path(), e.message() + " (sweep value " + spec.pointer + " = " + Significant(v, 10) + ")",
                       e.mentioned_parameters());
    }
  };
  // The work is estimated from the first value's case before anything else is parsed or allocated (issue 41: 1e6
  // values held 3.8 GB of parsed cases before the first run and killed the Python interpreter). Then every value is
  // parsed and checked, so that bad input stops the sweep before any run, naming the value that caused it; the cases
  // are not kept (each run parses its own again), so memory does not grow with the number of values.
  CheckSweepWork(parse(spec.values.front()), spec.values.size());
  for (double v : spec.values) parse(v);

  const Stopwatch clock;
  SweepResult result;
  result.points = ParallelMap(
      spec.values.size(), spec.jobs,
      [&](std::size_t i) {
        SweepPoint p;
        p.value = spec.values[i];
        try {
          p.summary = RunCase(parse(spec.values[i])).summary;
          p.ok = true;
        } catch (const NumericalError& e) {
          p.error = e.what();
        }
        return p;
      },
      [&](const SweepPoint& p, std::size_t done, std::size_t total) {
        if (progress) progress(p, static_cast<int>(done), static_cast<int>(total));
      });
  result.wall_time_s = clock.Seconds();
  return result;
}

void WriteSweepOutputs(const nlohmann::json& document, const SweepSpec& spec, const SweepResult& result,
                       const std::string& out_dir) {
  // Columns: the parameter, ok, then every numeric key any successful run reported (sorted, as JSON keeps them).
  std::set<std::string> keys;
  for (const SweepPoint& p : result.points)
    if (p.ok)
      for (const auto& item : p.summary.items())
        if (item.value().is_number() || item.value().is_null()) keys.insert(item.key());
  std::vector<std::string> header{spec.pointer, "ok"};
  header.insert(header.end(), keys.begin(), keys.end());
  std::vector<std::vector<double>> columns(header.size());
  for (const SweepPoint& p : result.points) {
    columns[0].push_back(p.value);
    columns[1].push_back(p.ok ? 1.0 : 0.0);
    std::size_t j = 2;
    for (const std::string& key : keys) {
      const bool has = p.ok && p.summary.contains(key) && p.summary.at(key).is_number();
      columns[j++].push_back(has ? p.summary.at(key).get<double>() : std::nan(""));
    }
  }
  auto column = [&](const std::string& key) -> const std::vector<double>* {
    const auto it = std::find(header.begin(), header.end(), key);
    return it == header.end() ? nullptr : &columns[static_cast<std::size_t>(it - header.begin())];
  };

  io::OutputDirectory out(out_dir);
  // A pointer may contain ',' (not in drillwave's own keys, but JSON allows it): the CSV names it by its last part.
  std::vector<std::string> csv_header = header;
  if (csv_header[0].find_first_of(",\"\n") != std::string::npos) csv_header[0] = "parameter";
  io::WriteCsv(out.Open("sweep.csv"), csv_header, columns);
  out.Open("case.json") << document.dump(2) << "\n";

  const std::string name = document.value("name", std::string("case"));
  io::Figure figure;
  figure.title = name + ": sweep of " + spec.pointer;
  figure.x_label = io::AxisLabel(io::QuantityOfPointer(spec.pointer));
  io::Panel speeds{"bit speed over the window [rad/s]", {}};
  for (const char* key : {"bit_speed_max_rad_s", "bit_speed_mean_rad_s", "bit_speed_min_rad_s"})
    if (const auto* c = column(key)) speeds.series.push_back({key, columns[0], *c});
  if (!speeds.series.empty()) figure.panels.push_back(speeds);
  io::Panel sticking{"stick fraction", {}};
  if (const auto* c = column("stick_fraction")) sticking.series.push_back({"stick_fraction", columns[0], *c});
  if (!sticking.series.empty()) figure.panels.push_back(sticking);
  if (!figure.panels.empty()) io::WriteSvg(figure, out.Open("bifurcation.svg"));

  std::ostream& report = out.Open("report.md");
  int failed = 0;
  for (const SweepPoint& p : result.points) failed += p.ok ? 0 : 1;
  report << "# Sweep of " << spec.pointer << " for " << name << "\n\n"
         << result.points.size() << " runs (" << failed << " failed numerically) on " << spec.jobs
         << " thread(s) in " << result.wall_time_s << " s wall time. Each run starts from the case's own initial "
         << "state; statistics over the case's window.\n\n";
  report << "| " << spec.pointer << " | stick onsets | stick fraction | bit speed min | mean | max [rad/s] |\n"
         << "|---|---|---|---|---|---|\n";
  for (const SweepPoint& p : result.points) {
    report << "| " << Significant(p.value, 10) << " | ";
    if (!p.ok) {
      report << "failed: " << p.error << " | | | | |\n";
      continue;
    }
    for (const char* key : {"stick_onsets", "stick_fraction", "bit_speed_min_rad_s", "bit_speed_mean_rad_s",
                            "bit_speed_max_rad_s"})
      report << (p.summary.contains(key) ? p.summary.at(key).dump() : "") << " | ";
    report << "\n";
  }
  report << "\nFiles: `sweep.csv` (every numeric summary key per value), `bifurcation.svg`, `case.json` (the base "
            "case).\n";
  out.Commit();
}

}  // namespace drillwave::cases
