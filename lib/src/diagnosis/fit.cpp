#include "drillwave/diagnosis/fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/core/validity.hpp"
#include "drillwave/diagnosis/minimize.hpp"
#include "drillwave/io/json_reader.hpp"
#include "drillwave/io/output_dir.hpp"
#include "drillwave/io/axis_label.hpp"
#include "drillwave/io/svg_plot.hpp"

namespace drillwave::diagnosis {
namespace {

constexpr double kFailed = 1e6;  // objective of a run that cannot be made (invalid combination, numerical failure)

double Objective(const Comparison& c, const std::vector<std::string>& features) {
  double sum = 0;
  for (const std::string& name : features)
    for (const FeatureDifference& d : c.features)
      if (d.feature == name) {
        // A feature the recording has and the model lacks (no stick-slip at all, say) counts as 100 % off.
        const double rel = std::isfinite(d.relative) ? d.relative : (std::isfinite(d.recording) ? 1.0 : 0.0);
        sum += rel * rel;
      }
  return sum;
}

}  // namespace

FitParameter ParseFitParameter(const std::string& text) {
  const auto a = text.find(':'), b = text.rfind(':');
  if (text.empty() || text[0] != '/' || a == std::string::npos || a == b)
    throw ParameterError("param", "'" + text + "': expected /json/pointer:lower:upper");
  FitParameter p{text.substr(0, a), 0, 0};
  char* end = nullptr;
  const std::string lo = text.substr(a + 1, b - a - 1), hi = text.substr(b + 1);
  p.lower = std::strtod(lo.c_str(), &end);
  const bool lo_ok = !lo.empty() && end == lo.c_str() + lo.size();
  p.upper = std::strtod(hi.c_str(), &end);
  const bool hi_ok = !hi.empty() && end == hi.c_str() + hi.size();
  if (!lo_ok || !hi_ok || !std::isfinite(p.lower) || !std::isfinite(p.upper) || !(p.lower < p.upper))
    throw ParameterError("param", "'" + ReadableText(text) + "': " +
                                    (lo_ok && hi_ok && p.lower > p.upper ? "the bounds are reversed; " : "") +
                                    "the bounds must be finite numbers with lower < upper");
  return p;
}

double CaseValue(const nlohmann::json& document, const FitParameter& p) {
  nlohmann::json::json_pointer ptr;
  try {
    ptr = nlohmann::json::json_pointer(p.pointer);
  } catch (const nlohmann::json::exception&) {
    throw InputError(p.pointer, "not a JSON pointer");
  }
  if (!document.contains(ptr) || !document.at(ptr).is_number())
    throw InputError(p.pointer, "expected a number in the case at this pointer");
  if (!(p.lower < p.upper)) throw InputError(p.pointer, "expected lower < upper");
  return document.at(ptr).get<double>();
}

bool FitOptions::IsValid(std::string* error) const {
  return OrderedFields(error, "window_begin_s", window_begin_s, "window_end_s", window_end_s,
                       "the window must end after it begins") &&
         (!features.empty() || Invalid(error, "features", "expected at least one feature to match, got none")) &&
         FiniteField(error, "model_time_offset_s", model_time_offset_s) &&
         WholeField(error, "max_evaluations", max_evaluations, 1) &&
         ((tolerance > 0 && tolerance <= 1) ||
          Invalid(error, "tolerance", "expected a share of each parameter's range in (0, 1], got " +
                                          ReadableNumber(tolerance))) &&
         WholeField(error, "starts", starts, 1);
}

FitResult FitFeatures(const nlohmann::json& document, const Recording& recording,
                      const std::vector<FitParameter>& parameters, const FitOptions& o, const FitProgress& progress) {
  ThrowIfInvalid(o);
  if (parameters.empty()) throw ParameterError("param", "no parameter to fit");
  const std::size_t k = parameters.size();
  std::vector<double> start(k);
  for (std::size_t i = 0; i < k; ++i)
    start[i] = std::clamp(CaseValue(document, parameters[i]), parameters[i].lower, parameters[i].upper);
  FitResult result;
  result.start = start;

  auto values_of = [&](const std::vector<double>& u) {
    std::vector<double> v(k);
    for (std::size_t i = 0; i < k; ++i)
      v[i] = parameters[i].lower + std::clamp(u[i], 0.0, 1.0) * (parameters[i].upper - parameters[i].lower);
    return v;
  };
  auto document_with = [&](const std::vector<double>& v) {
    nlohmann::json doc = document;
    for (std::size_t i = 0; i < k; ++i) io::SetByPointer(doc, parameters[i].pointer, v[i]);
    return doc;
  };
  auto compare = [&](const std::vector<double>& v) {
    cases::CaseRun run = cases::RunCase(cases::ParseCase(document_with(v)));
    for (double& t : run.result.time_s) t -= o.model_time_offset_s;
    return Compare(recording, run.result, o.maps, o.window_begin_s, o.window_end_s);
  };

  // The start must run, and every feature asked for must exist: bad input stops here.
  result.before = compare(start);
  for (const std::string& name : o.features)
    if (std::none_of(result.before.features.begin(), result.before.features.end(),
                     [&](const FeatureDifference& d) { return d.feature == name; })) {
      std::string list;
      for (const auto& d : result.before.features) list += (list.empty() ? "" : ", ") + d.feature;
      throw ParameterError("feature", "no feature named " + name + " (there are: " + list + ")");
    }
  result.objective_start = Objective(result.before, o.features);

  auto objective = [&](const std::vector<double>& u) {
    ++result.evaluations;
    const std::vector<double> v = values_of(u);
    double f;
    try {
      f = Objective(compare(v), o.features);
    } catch (const InputError&) {  // a combination the case rejects (e.g. mu_s below mu_c)
      f = kFailed, ++result.failed_runs;
    } catch (const NumericalError&) {
      f = kFailed, ++result.failed_runs;
    }
    if (progress) progress(result.evaluations, f, v);
    return f;
  };

  // NLopt's bounded Subplex in the unit cube of the bounds (minimize.hpp).
  std::vector<double> unit_start(k);
  for (std::size_t i = 0; i < k; ++i)
    unit_start[i] = (start[i] - parameters[i].lower) / (parameters[i].upper - parameters[i].lower);
  MinimizeOptions mo;
  mo.max_evaluations = o.max_evaluations;
  mo.x_tolerance = o.tolerance;
  mo.starts = o.starts;
  const MinimizeResult best = MinimizeInUnitCube(objective, unit_start, mo);
  result.fitted = values_of(best.best);
  result.document = document_with(result.fitted);
  result.after = compare(result.fitted);
  result.objective_fitted = Objective(result.after, o.features);
  return result;
}

void WriteFit(const Recording& recording, const FitOptions& o, const std::vector<FitParameter>& parameters,
              const FitResult& r, const std::string& out_dir) {
  io::OutputDirectory out(out_dir);
  out.Open("fitted-case.json") << r.document.dump(2) << "\n";
  nlohmann::json fitted = nlohmann::json::array();
  for (std::size_t i = 0; i < parameters.size(); ++i)
    fitted.push_back({{"pointer", parameters[i].pointer},
                      {"bounds", {parameters[i].lower, parameters[i].upper}},
                      {"start", r.start[i]},
                      {"fitted", r.fitted[i]}});
  out.Open("fit.json") << nlohmann::json{{"parameters", fitted},
                                         {"features", o.features},
                                         {"objective_start", r.objective_start},
                                         {"objective_fitted", r.objective_fitted},
                                         {"evaluations", r.evaluations},
                                         {"failed_runs", r.failed_runs},
                                         {"before", ComparisonToJson(r.before)},
                                         {"after", ComparisonToJson(r.after)}}
                                      .dump(2)
                               << "\n";
  io::Figure figure;
  figure.title = "fitted model against " + recording.source;
  figure.x_label = "time [s]";
  std::vector<double> t;
  for (double ti : recording.time_s)
    if (ti >= r.after.window_begin_s && ti <= r.after.window_end_s) t.push_back(ti);
  for (std::size_t j = 0; j < o.maps.size(); ++j)
    figure.panels.push_back({io::AxisLabelOfChannels({o.maps[j].recording}),
                             {{o.maps[j].recording + " (recording, artefacts masked)", t, r.after.recording.cleaned[j]},
                              {o.maps[j].model + " (fitted model)", t, r.after.model.cleaned[j]}}});
  io::WriteSvg(figure, out.Open("plot.svg"));
  std::ostream& report = out.Open("report.md");
  report << "# Fit against " << recording.source << "\n\n" << r.evaluations << " model runs (" << r.failed_runs
         << " rejected or failed); objective (sum of squared relative feature differences) "
         << Significant(r.objective_start, 4) << " at the start, " << Significant(r.objective_fitted, 4)
         << " fitted.\n\n| parameter | bounds | start | fitted |\n|---|---|---|---|\n";
  for (std::size_t i = 0; i < parameters.size(); ++i)
    report << "| " << parameters[i].pointer << " | [" << Significant(parameters[i].lower, 6) << ", "
           << Significant(parameters[i].upper, 6) << "] | " << Significant(r.start[i], 6) << " | "
           << Significant(r.fitted[i], 6) << " |\n";
  report << "\n| feature | recording | model before | model after |\n|---|---|---|---|\n";
  for (const FeatureDifference& b : r.before.features)
    for (const FeatureDifference& a : r.after.features)
      if (a.feature == b.feature)
        report << "| " << b.feature << (std::find(o.features.begin(), o.features.end(), b.feature) != o.features.end() ? " (fitted)" : "")
               << " | " << Significant(b.recording, 5) << " | " << Significant(b.model, 5) << " | "
               << Significant(a.model, 5) << " |\n";
  report << "\nFiles: `fitted-case.json` (run it with `drillwave run`), `fit.json`, `plot.svg`.\n";
  out.Commit();
}

}  // namespace drillwave::diagnosis
