// drillwave command-line tool: thin layer over the library. Exit codes: 0 success, 1 an expectation failed (--check),
// 2 bad input (the message names the JSON path or option, the value and what was expected; checked before any work
// starts), 3 numerical failure (with time and state), 4 internal error (with its message), 5 the outputs could not be
// written after the work (disk full, a file-size limit: the file and the cause; the output folder is left as it was).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/cases/controller_comparison.hpp"
#include "drillwave/cases/controller_envelope.hpp"
#include "drillwave/cases/edge_tracking.hpp"
#include "drillwave/cases/orbits.hpp"
#include "drillwave/cases/stability.hpp"
#include "drillwave/cases/stability_map.hpp"
#include "drillwave/cases/sweep.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/core/memory.hpp"
#include "drillwave/core/parallel.hpp"
#include "drillwave/core/progress.hpp"
#include "drillwave/core/validity.hpp"
#include "drillwave/diagnosis/comparison.hpp"
#include "drillwave/diagnosis/sidecar.hpp"
#include "drillwave/diagnosis/loop_report.hpp"
#include "drillwave/io/output_dir.hpp"
#include "drillwave/diagnosis/fit.hpp"
#include "drillwave/diagnosis/inspection.hpp"
#include "drillwave/diagnosis/posterior.hpp"
#include "drillwave/estimation/follow.hpp"
#include "drillwave/estimation/recording_estimate.hpp"
#include "drillwave/io/json_reader.hpp"

namespace {

// Options fields (core/validity.hpp) this tool sets by a flag of another name.
const std::map<std::string, std::string> kFlagsOfFields = {
    {"threads", "--jobs"},
    {"evaluations_per_parameter", "--evaluations"},
    {"sample_window_s", "--sample-window"},
    {"fit_begin_s", "--fit-window"},
    {"fit_end_s", "--fit-window"},
    {"held_out_begin_s", "--held-out"},
    {"held_out_end_s", "--held-out"},
    {"window_begin_s", "--window"},
    {"window_end_s", "--window"},
    {"bit_speed", "--bit"},
    {"top_speed", "--top"},
    {"telemetry_delay_s", "--fuse-delay"},
    {"innovation_time_constant_s", "--fuse-time-constant"}};

// The flag that sets a library parameter (drillwave::ParameterError names it as the library does): "max_samples"
// -> "--max-samples", an options field by kFlagsOfFields; a parameter with a qualifier ("map /model/bit/inertia_kgm2")
// keeps it.
std::string FlagOf(const std::string& parameter) {
  const std::size_t space = parameter.find(' ');
  const std::string name = parameter.substr(0, space);
  const auto other = kFlagsOfFields.find(name);
  std::string flag = other != kFlagsOfFields.end() ? other->second : "--" + name;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return space == std::string::npos ? flag : flag + parameter.substr(space);
}

// An input error as this tool's user sets things: a library parameter it names, and those its message advises,
// by their flags.
std::string InTermsOfFlags(const drillwave::InputError& e) {
  std::string message = e.message();
  for (const std::string& parameter : e.mentioned_parameters()) {
    const std::string flag = FlagOf(parameter);
    auto is_word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    for (std::size_t at = message.find(parameter); at != std::string::npos; at = message.find(parameter, at)) {
      const std::size_t end = at + parameter.size();
      if ((at > 0 && is_word(message[at - 1])) || (end < message.size() && is_word(message[end]))) {
        at = end;
        continue;
      }
      message.replace(at, parameter.size(), flag);
      at += flag.size();
    }
  }
  const bool parameter = dynamic_cast<const drillwave::ParameterError*>(&e) != nullptr;
  const std::string where = parameter ? FlagOf(e.json_path()) : e.json_path();
  return where.empty() ? message : where + ": " + message;
}

using drillwave::cases::Case;

nlohmann::json LoadCaseDocument(const std::string& file, const std::vector<std::string>& overrides) {
  nlohmann::json doc = file.empty() ? drillwave::io::ParseJsonText(drillwave::cases::DefaultCaseText(), "the default case")
                                    : drillwave::io::LoadJsonFile(file);
  for (const std::string& o : overrides) drillwave::io::ApplySetOption(doc, o);
  return doc;
}

int RunAndWrite(const std::string& file, const std::string& out_dir, const std::vector<std::string>& overrides,
                bool check) {
  const Case c = drillwave::cases::ParseCase(LoadCaseDocument(file, overrides));
  drillwave::io::OutputDirectory::CheckReplaceable(out_dir);
  {  // trajectory.csv dominates the outputs: samples x (time and channels) x about 12 bytes a number, plus the rest;
     // in memory the run holds them as 8-byte numbers
    const double samples = c.settings.duration_s / c.settings.output_interval_s + 1;
    auto bytes = [&](double channels) { return samples * (channels + 1) * 12 + 5e5; };
    auto memory = [&](double channels) { return samples * (channels + 1) * 8; };
    const std::string remedy = "ask for fewer samples (a longer /simulation/output_interval_s or a shorter "
                               "/simulation/duration_s), or free memory";
    try {  // a generous estimate first; the kind's own channels (a probe of a few samples) only when it does not fit
      drillwave::io::OutputDirectory::CheckFreeSpace(out_dir, bytes(32));
      drillwave::CheckMemory(memory(32), "the run's trajectory", remedy);
    } catch (const std::runtime_error&) {
      const double channels = static_cast<double>(drillwave::diagnosis::ProbeChannels(c).size());
      drillwave::io::OutputDirectory::CheckFreeSpace(out_dir, bytes(channels));
      drillwave::CheckMemory(memory(channels), "the run's trajectory", remedy);
    }
  }
  std::cout << "drillwave: running case '" << c.name << "' (kind " << c.kind << ", " << c.settings.duration_s
            << " s simulated)" << (file.empty() ? " [embedded default case]" : "") << std::endl;
  auto run = drillwave::cases::RunCase(c);
  drillwave::cases::AddLinearVerdict(c, run.summary);
  drillwave::cases::WriteCaseOutputs(c, run, out_dir);
  const auto dir = std::filesystem::absolute(out_dir).string();
  std::cout << "wall time " << run.summary.value("wall_time_s", 0.0) << " s, " << run.summary.value("steps", 0)
            << " steps, " << run.summary.value("events", 0) << " events\n";
  for (const char* key : {"stick_slip_period_s", "stick_fraction", "bit_speed_mean_rad_s", "bit_speed_max_rad_s"})
    if (run.summary.contains(key)) std::cout << "  " << key << " = " << run.summary.at(key).dump() << "\n";
  if (run.summary.contains("linear_verdict"))
    std::cout << "  note: " << run.summary.at("linear_verdict").get<std::string>() << "\n";
  std::cout << "wrote " << dir << "/trajectory.csv (sampled channels), summary.json (statistics), plot.svg (figure), "
            << "report.md (report), case.json (the case as run)\n";
  bool all_passed = true;
  for (const auto& e : drillwave::cases::CheckExpectations(c.expect, run.summary)) {
    std::cout << "  expect " << (e.passed ? "PASS " : "FAIL ") << e.detail << "\n";
    all_passed &= e.passed;
  }
  return check && !all_passed ? 1 : 0;
}

int Sweep(const std::string& file, const std::string& out_dir, const std::vector<std::string>& overrides,
          const std::string& pointer, const std::string& values_text, int jobs) {
  const nlohmann::json doc = LoadCaseDocument(file, overrides);
  drillwave::cases::SweepSpec spec{pointer, drillwave::cases::ParseSweepValues(values_text, "values"), jobs};
  drillwave::io::OutputDirectory::CheckReplaceable(out_dir);
  std::cout << "drillwave: sweeping " << pointer << " over " << spec.values.size() << " values on " << jobs
            << " thread(s)" << (file.empty() ? " [embedded default case]" : "") << std::endl;
  const auto result = drillwave::cases::RunSweep(
      doc, spec, [&](const drillwave::cases::SweepPoint& p, int done, int total) {
        std::cout << "  [" << done << "/" << total << "] " << pointer << " = " << p.value << ": ";
        if (!p.ok) {
          std::cout << "numerical failure: " << p.error << std::endl;
          return;
        }
        for (const char* key : {"stick_onsets", "stick_fraction", "bit_speed_min_rad_s", "bit_speed_max_rad_s"})
          if (p.summary.contains(key)) std::cout << key << " " << p.summary.at(key).dump() << "  ";
        std::cout << std::endl;
      });
  drillwave::cases::WriteSweepOutputs(doc, spec, result, out_dir);
  int failed = 0;
  for (const auto& p : result.points) failed += p.ok ? 0 : 1;
  std::cout << "wall time " << result.wall_time_s << " s; wrote " << std::filesystem::absolute(out_dir).string()
            << "/sweep.csv, bifurcation.svg, report.md, case.json" << std::endl;
  if (failed > 0) {
    std::cerr << "drillwave: " << failed << " of " << result.points.size()
              << " runs failed numerically (recorded in sweep.csv with ok = 0 and in report.md)" << std::endl;
    return 3;
  }
  return 0;
}

int StabilityMap2D(const std::string& file, const std::string& out_dir, const std::vector<std::string>& overrides,
                   const std::vector<std::string>& axes, bool simulate, bool full_spectrum, int jobs,
                   const std::string& draws_file, int draw_count) {
  const nlohmann::json doc = LoadCaseDocument(file, overrides);
  if (axes.size() != 2)
    throw drillwave::InputError("--map", "expected two axes, POINTER1=first:last:n POINTER2=first:last:n");
  const drillwave::cases::StabilityMapSpec spec{drillwave::cases::ParseMapAxis(axes[0], doc),
                                                drillwave::cases::ParseMapAxis(axes[1], doc), jobs, simulate,
                                                full_spectrum};
  if (jobs < 1) throw drillwave::InputError("-j", "expected a whole number >= 1, got " + std::to_string(jobs));
  drillwave::io::OutputDirectory::CheckReplaceable(out_dir);
  std::cout << "drillwave: stability map " << spec.x.pointer << " (" << spec.x.values.size() << ") x "
            << spec.y.pointer << " (" << spec.y.values.size() << ") on " << jobs << " thread(s)"
            << (simulate ? ", with a simulation per point" : "") << std::endl;
  drillwave::cases::StabilityMapResult result;
  if (draws_file.empty()) {
    result = drillwave::cases::StabilityMap2D(doc, spec);
  } else {
    const auto draws = drillwave::cases::ReadParameterDraws(draws_file, doc, draw_count);
    std::cout << "  over " << draws.rows.size() << " parameter draws from " << draws_file << " and the case itself"
              << std::endl;
    result = drillwave::cases::StabilityMapOverDraws(doc, spec, draws, [](int done, int n) {
      if (done % std::max(1, n / 10) == 0 || done == n)
        std::cout << "  " << done << " of " << n << " draws mapped" << std::endl;
    });
  }
  drillwave::cases::WriteStabilityMap2D(doc, spec, result, out_dir);
  std::cout << "linear analysis " << result.linear_wall_time_s << " s (full spectrum at " << result.full_spectra
            << " steady states)";
  if (simulate) std::cout << ", simulations " << result.simulation_wall_time_s << " s";
  std::cout << "\nwrote " << std::filesystem::absolute(out_dir).string()
            << "/stability_map.csv, stability_map.svg, " << (result.draws > 0 ? "p_stick_slip.svg, " : "")
            << "report.md, case.json" << std::endl;
  return 0;
}

int Stability(const std::string& file, const std::string& out_dir, const std::vector<std::string>& overrides,
              const std::string& pointer, const std::string& values_text, int jobs, bool run_from_start) {
  const nlohmann::json doc = LoadCaseDocument(file, overrides);
  const auto dir = std::filesystem::absolute(out_dir).string();
  drillwave::io::OutputDirectory::CheckReplaceable(out_dir);
  if (!pointer.empty()) {
    const drillwave::cases::SweepSpec spec{pointer, drillwave::cases::ParseSweepValues(values_text, "values"), jobs};
    const auto rows = drillwave::cases::StabilityMap(doc, spec);
    drillwave::cases::WriteStabilityMap(doc, spec, rows, out_dir);
    int stable = 0;
    for (const auto& r : rows) stable += r.stable ? 1 : 0;
    std::cout << "drillwave: stability map over " << pointer << ": " << spec.values.size() << " values, "
              << rows.size() << " steady states, " << stable << " stable\nwrote " << dir
              << "/stability_map.csv, stability_map.svg, report.md, case.json" << std::endl;
    return 0;
  }
  const drillwave::cases::Case c = drillwave::cases::ParseCase(doc);
  const auto result = drillwave::cases::AnalyzeStability(c);
  std::cout << "drillwave: linearized stability of '" << c.name << "' (kind " << c.kind << "): " << result.size()
            << " steady state(s)" << std::endl;
  for (std::size_t k = 0; k < result.size(); ++k) {
    const auto& sp = result[k].spectrum;
    std::cout << "  [" << k << "] " << result[k].point.steady_state.dump() << "\n      "
              << drillwave::analysis::VerdictName(sp.verdict) << ": rightmost root " << sp.spectral_abscissa
              << (sp.roots.empty() ? "" : " " + std::string(sp.roots[0].s.imag() >= 0 ? "+ " : "- ") +
                                              std::to_string(std::abs(sp.roots[0].s.imag())) + "i")
              << ", essential spectrum at Re s = " << sp.essential_abscissa << std::endl;
    if (sp.verdict == drillwave::analysis::Spectrum::Verdict::kMarginal)
      std::cout << "      marginal: the essential spectrum lies on the imaginary axis (lossless reflections at both "
                   "ends at high frequency); no root found right of it up to |Im s| = 200, but no uniform decay rate"
                << std::endl;
    if (const auto& continuum = result[k].continuum) {
      const auto& cs = continuum->spectrum;
      std::cout << "      continuum string (exact Kelvin-Voigt sections; the verdict above is the discretized model's): "
                << drillwave::analysis::VerdictName(cs.verdict) << ", rightmost root " << cs.spectral_abscissa
                << (cs.roots.empty() ? "" : " + " + std::to_string(cs.roots[0].s.imag()) + "i")
                << (continuum->certified ? "" : " (not certified)") << std::endl;
    }
  }
  // A stable steady state may share the phase space with a stick-slip cycle: the run from the case's start tells.
  std::optional<drillwave::cases::RunFromStart> from_start;
  if (run_from_start) {
    std::cout << "  running the case from its start (" << c.settings.duration_s << " s simulated; --no-run skips it)"
              << std::endl;
    from_start = drillwave::cases::CompareWithRunFromStart(c, result);
    if (from_start->ran)
      std::cout << "  from its start the bit " << (from_start->sticks ? "sticks and slips" : "does not stick")
                << " (stick fraction " << from_start->stick_fraction << ")" << std::endl;
    if (!from_start->note.empty()) std::cout << "  note: " << from_start->note << std::endl;
  }
  drillwave::cases::WriteStabilityOutputs(c, result, out_dir, from_start ? &*from_start : nullptr);
  std::cout << "wrote " << dir << "/stability.json, roots.csv, report.md, case.json" << std::endl;
  return 0;
}

int Inspect(const std::string& file, const std::string& out_dir, const std::string& bit, const std::string& top) {
  drillwave::diagnosis::InspectOptions options;
  options.bit_speed = bit;
  options.top_speed = top;
  drillwave::ThrowIfInvalid(options);
  const auto recording = drillwave::diagnosis::LoadRecording(file);
  drillwave::io::OutputDirectory::CheckReplaceable(out_dir);
  const auto inspection = drillwave::diagnosis::InspectRecording(recording, options);
  drillwave::diagnosis::WriteInspection(recording, inspection, out_dir);
  std::cout << "drillwave: inspected " << file << " (" << recording.names.size() << " channels, "
            << recording.time_s.size() << " samples)" << std::endl;
  for (const auto& f : inspection.findings) std::cout << "  - " << f << "\n";
  std::cout << "wrote " << std::filesystem::absolute(out_dir).string() << "/findings.json, report.md, plot.svg"
            << std::endl;
  return 0;
}

// "begin,end" (empty: everything).
std::pair<double, double> Window(const std::string& text) {
  const double inf = std::numeric_limits<double>::infinity();
  if (text.empty()) return {-inf, inf};
  const auto values = drillwave::cases::ParseSweepValues(text, "window");
  if (values.size() != 2)
    throw drillwave::InputError("--window", "'" + drillwave::ReadableText(text) + "': expected begin,end [s]");
  if (values[1] < values[0])
    throw drillwave::InputError("--window", "'" + drillwave::ReadableText(text) +
                                                "' is reversed; expected begin,end with begin < end");
  if (!(values[1] > values[0]))
    throw drillwave::InputError("--window", "'" + drillwave::ReadableText(text) +
                                                "' is empty; expected begin,end with begin < end");
  return {values[0], values[1]};
}

// The model's time span as the comparison sees it (recording time: the warm-up before the recording subtracted).
std::pair<double, double> ModelSpan(const Case& c, double offset_s) {
  return {-offset_s, c.settings.duration_s - offset_s};
}

nlohmann::json LoadSidecar(const std::string& sidecar_file, const nlohmann::json& doc, double warmup_s) {
  return drillwave::diagnosis::CaseFromSidecar(drillwave::io::LoadJsonFile(sidecar_file), doc, warmup_s, sidecar_file);
}

int Compare(const std::string& file, const std::string& recording_file, const std::string& sidecar_file,
            const std::vector<std::string>& overrides, const std::vector<std::string>& map_texts,
            const std::string& window, const std::string& out_dir) {
  namespace dg = drillwave::diagnosis;
  nlohmann::json doc = LoadCaseDocument(file, overrides);
  // With a sidecar, the model runs the warm-up first and is compared in recording time, from 5 s on by default.
  const double offset = sidecar_file.empty() ? 0 : dg::kSidecarWarmupS;
  if (!sidecar_file.empty()) doc = LoadSidecar(sidecar_file, doc, offset);
  const drillwave::cases::Case c = drillwave::cases::ParseCase(doc);
  const dg::Recording recording = dg::LoadRecording(recording_file);
  auto [begin, end] = Window(window);
  if (window.empty() && !sidecar_file.empty()) begin = 5;
  const auto [model_begin, model_end] = ModelSpan(c, offset);
  dg::CheckWindow(recording, model_begin, model_end, begin, end);
  const auto maps = dg::ResolveChannelMaps(map_texts, recording, dg::ProbeChannels(c));
  drillwave::io::OutputDirectory::CheckReplaceable(out_dir);
  std::cout << "drillwave: running case '" << c.name << "' (kind " << c.kind << ", " << c.settings.duration_s
            << " s simulated) against " << recording_file << std::endl;
  auto run = drillwave::cases::RunCase(c);
  for (double& t : run.result.time_s) t -= offset;  // recording time
  const dg::Comparison comparison = dg::Compare(recording, run.result, maps, begin, end);
  dg::WriteComparison(recording, run.result, maps, comparison, out_dir);
  for (const auto& f : comparison.findings) std::cout << "  - " << f << "\n";
  std::cout << "wrote " << std::filesystem::absolute(out_dir).string() << "/comparison.json, report.md, plot.svg"
            << std::endl;
  return 0;
}


int Fit(const std::string& file, const std::string& recording_file, const std::string& sidecar_file,
        const std::vector<std::string>& overrides,
        const std::vector<std::string>& map_texts, const std::string& window, const std::vector<std::string>& params,
        const std::vector<std::string>& features, int max_evaluations, const std::string& out_dir) {
  namespace dg = drillwave::diagnosis;
  nlohmann::json doc = LoadCaseDocument(file, overrides);
  dg::FitOptions options;
  if (!sidecar_file.empty()) {  // the synthetic recordings' operating point, with the warm-up before the recording
    doc = LoadSidecar(sidecar_file, doc, dg::kSidecarWarmupS);
    options.model_time_offset_s = dg::kSidecarWarmupS;
    options.window_begin_s = 5;
  }
  if (!window.empty()) std::tie(options.window_begin_s, options.window_end_s) = Window(window);
  if (!features.empty()) options.features = features;
  options.max_evaluations = max_evaluations;
  drillwave::ThrowIfInvalid(options);
  const drillwave::cases::Case c = drillwave::cases::ParseCase(doc);
  const dg::Recording recording = dg::LoadRecording(recording_file);
  const auto [model_begin, model_end] = ModelSpan(c, options.model_time_offset_s);
  dg::CheckWindow(recording, model_begin, model_end, options.window_begin_s, options.window_end_s);
  options.maps = dg::ResolveChannelMaps(map_texts, recording, dg::ProbeChannels(c));
  const std::vector<std::string> known = dg::FeatureNames(options.maps);
  for (const std::string& f : options.features)
    if (std::find(known.begin(), known.end(), f) == known.end()) {
      std::string list;
      for (const std::string& k : known) list += (list.empty() ? "" : ", ") + k;
      throw drillwave::InputError("--feature", "no feature named '" + drillwave::ReadableText(f) +
                                                   "' (with these channel maps there are: " + list + ")");
    }
  std::vector<dg::FitParameter> parameters;
  for (const std::string& p : params) {
    parameters.push_back(dg::ParseFitParameter(p));
    nlohmann::json probe = doc;  // the pointer must lead to a number in the case, and both bounds must be valid
    for (const double bound : {parameters.back().lower, parameters.back().upper}) {
      drillwave::io::SetByPointer(probe, parameters.back().pointer, bound);
      try {
        drillwave::cases::ParseCase(probe);
      } catch (const drillwave::InputError& e) {  // the bound itself out of the field's range; combinations may fail
        if (e.json_path() == parameters.back().pointer)
          throw drillwave::InputError("--param", "'" + drillwave::ReadableText(p) + "': the bound " +
                                                     drillwave::ReadableNumber(bound) + " is not valid: " + e.what());
      }
    }
  }
  drillwave::io::OutputDirectory::CheckReplaceable(out_dir);
  std::cout << "drillwave: fitting " << parameters.size() << " parameter(s) of '" << c.name << "' to "
            << recording_file << std::endl;
  const dg::FitResult r = dg::FitFeatures(doc, recording, parameters, options, [](int n, double f, const std::vector<double>& v) {
    std::cout << "  [" << n << "] objective " << f << " at";
    for (double x : v) std::cout << " " << x;
    std::cout << std::endl;
  });
  dg::WriteFit(recording, options, parameters, r, out_dir);
  std::cout << "objective " << r.objective_start << " -> " << r.objective_fitted << " in " << r.evaluations
            << " runs; fitted:";
  for (std::size_t i = 0; i < parameters.size(); ++i) std::cout << " " << parameters[i].pointer << " = " << r.fitted[i];
  std::cout << "\nwrote " << std::filesystem::absolute(out_dir).string()
            << "/fitted-case.json, fit.json, report.md, plot.svg" << std::endl;
  return 0;
}

// `estimate` (issue 34): the bit seen from the surface channels named in --from, scored against the downhole ones.
struct EstimateArguments {
  std::string from, window, out = "drillwave-estimate";
  bool follow = false;
  double follow_idle_s = 10;
  std::string fuse;  // downhole telemetry channels fused into the estimate
  drillwave::estimation::TelemetryFusion fusion;
  bool read_fuse_delay = true;  // --fuse-delay not given: read from the bit speed channel
};

// --follow: the recording read as it grows (or from standard input), each estimate row printed to standard output as
// soon as the latency allows; at the end (standard input closed, or the file idle for --follow-idle seconds) the
// output folder as without --follow, from the rows given out.
drillwave::estimation::BitEstimate FollowRecording(const drillwave::estimation::EstimatorModel& model,
                                                   const drillwave::estimation::EstimateOptions& options,
                                                   const EstimateArguments& a, const std::string& recording_file,
                                                   drillwave::diagnosis::Recording& recording,
                                                   double& estimating_s) {
  namespace es = drillwave::estimation;
  es::GrowingCsv csv(recording_file);
  std::vector<std::vector<double>> rows;
  constexpr double kPollS = 0.05;
  double idle_s = 0;
  bool more = true;
  while (csv.names().empty() && more && idle_s < a.follow_idle_s) {
    more = csv.Read(rows, kPollS);
    if (csv.names().empty()) std::this_thread::sleep_for(std::chrono::duration<double>(kPollS)), idle_s += kPollS;
  }
  if (csv.names().empty()) throw drillwave::InputError(csv.source(), "no header line arrived");
  drillwave::diagnosis::Recording header;
  header.source = csv.source();
  header.names = csv.names();
  es::LiveEstimator live(model, options, csv.names(), es::ParseSurfaceChannels(a.from, header));
  std::vector<es::EstimateRow> given_out;
  std::cout << "time_s,bit_rpm,bit_rpm_band,bit_torque_Nm,bit_torque_Nm_band,wob_N,wob_N_band,bit_stuck\n";
  const auto print = [&](const std::vector<es::EstimateRow>& out) {
    for (const es::EstimateRow& r : out) {
      std::cout << r.time_s << "," << r.bit_speed_rad_s / drillwave::kRadPerSecondPerRpm << ","
                << r.bit_speed_band_rad_s / drillwave::kRadPerSecondPerRpm << ","
                << r.bit_torque_Nm << "," << r.bit_torque_band_Nm << "," << r.wob_N << "," << r.wob_band_N << ","
                << (r.stuck ? 1 : 0) << "\n";
      given_out.push_back(r);
    }
    if (!out.empty()) std::cout.flush();
  };
  const auto timed = [&](const auto& work) {
    const auto begin = std::chrono::steady_clock::now();
    std::vector<es::EstimateRow> out = work();
    estimating_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
    return out;
  };
  print(timed([&] { return live.Push(rows); }));  // the rows that came with the header
  idle_s = 0;
  while (more && idle_s < a.follow_idle_s) {
    rows.clear();
    more = csv.Read(rows, kPollS);
    if (rows.empty()) {
      if (more) std::this_thread::sleep_for(std::chrono::duration<double>(kPollS)), idle_s += kPollS;
      continue;
    }
    idle_s = 0;
    print(timed([&] { return live.Push(rows); }));
  }
  print(timed([&] { return live.Finish(); }));
  recording = live.Recording();
  recording.source = csv.source();
  std::cerr << "drillwave: followed " << recording.time_s.size() << " rows of " << csv.source() << "; latency "
            << live.latency_s() << " s (estimates given out in stretches of 0.1 s)" << std::endl;
  return es::FromRows(given_out, live.stuck_threshold_rad_s(), live.latency_s(), live.method(), live.notes());
}

int Estimate(const std::string& file, const std::string& recording_file, const std::string& sidecar_file,
             const std::vector<std::string>& overrides, const EstimateArguments& a) {
  namespace es = drillwave::estimation;
  nlohmann::json doc = LoadCaseDocument(file, overrides);
  double hook_force_N = 0;
  es::EstimateOptions options;
  if (!sidecar_file.empty()) {
    const nlohmann::json sidecar = drillwave::io::LoadJsonFile(sidecar_file);
    doc = drillwave::diagnosis::CaseFromSidecar(sidecar, doc, drillwave::diagnosis::kSidecarWarmupS, sidecar_file);
    hook_force_N = 1000 * sidecar.value("hookload_setpoint_kN", 0.0);
    options.model_time_offset_s = -drillwave::diagnosis::kSidecarWarmupS;
  }
  drillwave::ThrowIfInvalid(options);
  drillwave::cases::ParseCase(doc);  // validates every field (InputError names its path)
  const es::EstimatorModel model = es::EstimatorModelFromCase(doc, hook_force_N);
  es::ScoreWindow score;
  if (!a.window.empty()) std::tie(score.begin_s, score.end_s) = Window(a.window);
  drillwave::io::OutputDirectory::CheckReplaceable(a.out);
  drillwave::diagnosis::Recording recording;
  es::BitEstimate e;
  double estimating_s = 0;  // the estimator's own time (reading and writing aside), for its throughput
  if (a.follow) {
    e = FollowRecording(model, options, a, recording_file, recording, estimating_s);
  } else {
    recording = drillwave::diagnosis::LoadRecording(recording_file);
    const es::SurfaceSignals signals =
        es::SignalsFromRecording(recording, es::ParseSurfaceChannels(a.from, recording));
    const auto begin = std::chrono::steady_clock::now();
    e = es::EstimateBit(model, signals, options);
    if (!a.fuse.empty()) es::FuseTelemetry(recording, a.fuse, a.fusion, a.read_fuse_delay, e);
    estimating_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  }
  const nlohmann::json summary = es::EstimateSummary(recording, e, score);
  es::WriteEstimate(recording, e, summary, a.out);
  std::ostream& report = a.follow ? std::cerr : std::cout;  // with --follow, standard output carries the rows
  report << "drillwave: estimated the bit from " << a.from << " (" << e.method << "), latency " << e.latency_s
         << " s\n";
  for (const auto& [key, value] : summary.at("errors").items())
    if (value.is_object()) report << "  " << key << ": " << value.dump() << "\n";
  const double span_s = recording.time_s.size() > 1 ? recording.time_s.back() - recording.time_s.front() : 0.0;
  report << "  throughput: " << recording.time_s.size() << " samples in " << estimating_s << " s of estimating, "
         << static_cast<double>(recording.time_s.size()) / std::max(estimating_s, 1e-9) << " samples/s, "
         << span_s / std::max(estimating_s, 1e-9) << " times real time\n";
  report << "wrote " << std::filesystem::absolute(a.out).string() << "/estimate.csv, estimate.json, plot.svg, report.html"
         << std::endl;
  return 0;
}

struct DiagnoseArguments {
  std::string fit_window, held_out;
  double margin = 0.2;
  double fit_tolerance = 1e-4;
  int threads = 1;
  int evaluations_per_parameter = 10;
  double sample_window_s = -1;  // < 0: the recording's sample interval
  int draws = 5;
  double predict_until_s = 0;  // > 0: the fitted model run on to this recording time (prediction.csv)
};

// The case, recording and loop options diagnose and calibrate share: the case (with a sidecar's operating point), the
// recording, its fit and held-out windows and sample window, the options a command sets (`set_options`), all checked
// (LoopOptions::IsValid) before the windows are checked against the model's span and the channel maps resolved.
struct LoopInputs {
  nlohmann::json doc;
  std::string case_name;
  drillwave::diagnosis::Recording recording;
  drillwave::diagnosis::LoopOptions o;
};

LoopInputs ReadLoopInputs(const std::string& file, const std::string& recording_file, const std::string& sidecar_file,
                          const std::vector<std::string>& overrides, const std::vector<std::string>& map_texts,
                          const std::string& fit_window, const std::string& held_out, double sample_window_s,
                          const std::function<void(drillwave::diagnosis::LoopOptions&)>& set_options = nullptr) {
  namespace dg = drillwave::diagnosis;
  LoopInputs in;
  in.doc = LoadCaseDocument(file, overrides);
  if (!sidecar_file.empty()) in.doc = LoadSidecar(sidecar_file, in.doc, dg::kSidecarWarmupS);
  const drillwave::cases::Case c = drillwave::cases::ParseCase(in.doc);
  in.case_name = c.name;
  in.recording = dg::LoadRecording(recording_file);
  dg::LoopOptions& o = in.o;
  o = dg::DefaultLoopOptions(c, in.recording, sidecar_file.empty() ? 0 : dg::kSidecarWarmupS);
  if (!fit_window.empty()) std::tie(o.fit_begin_s, o.fit_end_s) = Window(fit_window);
  if (!held_out.empty()) std::tie(o.held_out_begin_s, o.held_out_end_s) = Window(held_out);
  if (sample_window_s != -1) o.sample_window_s = sample_window_s;  // given
  if (set_options) set_options(o);
  drillwave::ThrowIfInvalid(o);
  const auto [model_begin, model_end] = ModelSpan(c, o.model_time_offset_s);
  dg::CheckWindow(in.recording, model_begin, model_end, o.fit_begin_s, o.fit_end_s);
  dg::CheckWindow(in.recording, model_begin, model_end, o.held_out_begin_s, o.held_out_end_s);
  o.maps = dg::ResolveChannelMaps(map_texts, in.recording, dg::ProbeChannels(c));
  return in;
}

int Diagnose(const std::string& file, const std::string& recording_file, const std::string& sidecar_file,
             const std::vector<std::string>& overrides, const std::vector<std::string>& map_texts,
             const DiagnoseArguments& a, const std::string& out_dir) {
  namespace dg = drillwave::diagnosis;
  const auto set_options = [&](dg::LoopOptions& o) {
    o.draws = a.draws;
    o.margin = a.margin;
    o.fit_tolerance = a.fit_tolerance;
    o.threads = a.threads;
    o.evaluations_per_parameter = a.evaluations_per_parameter;
  };
  LoopInputs in = ReadLoopInputs(file, recording_file, sidecar_file, overrides, map_texts, a.fit_window, a.held_out,
                                 a.sample_window_s, set_options);
  const nlohmann::json& doc = in.doc;
  const dg::Recording& recording = in.recording;
  const dg::LoopOptions& o = in.o;
  if (a.predict_until_s != 0) dg::CheckPredictionTime(o, a.predict_until_s);
  drillwave::io::OutputDirectory::CheckReplaceable(out_dir);
  std::cout << "drillwave: diagnosing " << recording_file << " with '" << in.case_name << "': fit window ["
            << o.fit_begin_s << ", " << o.fit_end_s << "] s, held out [" << o.held_out_begin_s << ", "
            << o.held_out_end_s << "] s" << std::endl;
  const dg::DiagnosisLoop loop =
      dg::RunDiagnosisLoop(doc, recording, o, [](const std::string& line) { std::cout << "  " << line << std::endl; });
  std::optional<dg::Recording> prediction;
  if (a.predict_until_s > 0) {
    std::cout << "  predicting with the fitted model up to " << a.predict_until_s << " s" << std::endl;
    prediction = dg::PredictFitted(loop, o, recording, a.predict_until_s);
  }
  dg::WriteDiagnosisLoop(loop, recording, out_dir, prediction ? &*prediction : nullptr);
  for (const auto& u : loop.unexplained) std::cout << "  unexplained: " << u << std::endl;
  std::cout << "wrote " << std::filesystem::absolute(out_dir).string()
            << "/diagnosis.json, fitted-case.json, case.json, report.html, plot.svg"
            << (prediction ? ", prediction.csv" : "") << std::endl;
  return 0;
}

struct CalibrateArguments {
  std::string fit_window, held_out;
  double sample_window_s = -1;
  std::vector<std::string> params;
  drillwave::diagnosis::PosteriorOptions posterior;
};

// The posterior of a case's parameters against a recording, with the diagnosis loop's feature likelihood.
int Calibrate(const std::string& file, const std::string& recording_file, const std::string& sidecar_file,
              const std::vector<std::string>& overrides, const std::vector<std::string>& map_texts,
              const CalibrateArguments& a, const std::string& out_dir) {
  namespace dg = drillwave::diagnosis;
  drillwave::ThrowIfInvalid(a.posterior);
  const LoopInputs in =
      ReadLoopInputs(file, recording_file, sidecar_file, overrides, map_texts, a.fit_window, a.held_out,
                     a.sample_window_s);
  std::vector<dg::FitParameter> parameters;
  for (const std::string& text : a.params) parameters.push_back(dg::ParseFitParameter(text));
  drillwave::io::OutputDirectory::CheckReplaceable(out_dir);
  std::cout << "drillwave: sampling the posterior of " << parameters.size() << " parameter(s) of '" << in.case_name
            << "' against " << recording_file << ": fit window [" << in.o.fit_begin_s << ", " << in.o.fit_end_s
            << "] s, held out [" << in.o.held_out_begin_s << ", " << in.o.held_out_end_s << "] s" << std::endl;
  const dg::Posterior post = dg::SamplePosterior(in.doc, in.recording, in.o, parameters, a.posterior,
                                                 [](const std::string& line) { std::cout << "  " << line << std::endl; });
  dg::WritePosterior(post, in.recording, out_dir);
  for (const dg::ParameterSummary& s : post.summaries)
    std::cout << "  " << s.pointer << ": median " << drillwave::Significant(s.q50, 5) << ", 90 % in ["
              << drillwave::Significant(s.q05, 5) << ", " << drillwave::Significant(s.q95, 5) << "]"
              << (std::abs(s.drift_sd) > dg::kMaxDrift ? " (still drifting: " + drillwave::Fixed(s.drift_sd, 2) +
                                                             " sd; run more steps)"
                                                       : std::string())
              << std::endl;
  std::cout << "wrote " << std::filesystem::absolute(out_dir).string()
            << "/posterior_samples.csv, posterior.json, predictive.csv, posterior.svg, map-case.json, report.md"
            << std::endl;
  return 0;
}

int ListKinds() {
  for (const auto& kind : drillwave::cases::AllKinds()) {
    std::cout << kind->name() << ": " << kind->description() << "\n" << kind->FieldSchema().dump(2) << "\n\n";
  }
  return 0;
}

// The saddle cycle between two attractors of a case, by edge tracking on one parameter of a perturbation.
int EdgeOrbit(const std::string& file, const std::string& out_dir, const std::vector<std::string>& overrides,
              const std::string& edge_text, const std::string& channel, double after_s, double tolerance) {
  const nlohmann::json doc = LoadCaseDocument(file, overrides);
  drillwave::io::OutputDirectory::CheckReplaceable(out_dir);
  drillwave::cases::EdgeSpec spec = drillwave::cases::ParseEdgeOption(edge_text, doc);
  if (!(tolerance > 0 && tolerance < 1))
    throw drillwave::InputError("--tolerance", drillwave::Significant(tolerance, 6) + " is not in (0, 1)");
  spec.tolerance = tolerance;
  std::cout << "drillwave: edge tracking on " << spec.pointer << " between " << spec.decays << " (decays) and "
            << spec.sticks << " (sticks)" << std::endl;
  const auto edge = drillwave::cases::TrackEdge(doc, spec, [](int runs, double decays, double sticks) {
    if (runs % 5 == 0 || runs == 2)
      std::cout << "  " << runs << " runs: boundary in [" << drillwave::Significant(decays, 12) << ", "
                << drillwave::Significant(sticks, 12) << "]" << std::endl;
  });
  const auto& names = edge.edge.channels;
  if (std::none_of(names.begin(), names.end(), [&](const auto& c) { return c.name == channel; }))
    throw drillwave::InputError("--channel", "the run has no channel '" + channel + "'");
  const auto cycle = drillwave::cases::FindShadowedCycle(edge.edge.time_s, edge.edge.channel(channel).values, after_s);
  drillwave::cases::WriteEdgeOutputs(doc, spec, edge, channel, after_s, cycle, out_dir);
  std::cout << "boundary in [" << drillwave::Significant(edge.decays, 12) << ", "
            << drillwave::Significant(edge.sticks, 12) << "] after " << edge.runs << " runs\n";
  if (cycle.found)
    std::cout << "saddle cycle: period " << drillwave::Significant(cycle.period_s, 6) << " s, " << channel
              << " peak-to-peak " << drillwave::Significant(cycle.amplitude, 6) << " (from t = "
              << drillwave::Significant(cycle.time_s, 6) << " s, changing " << drillwave::Significant(100 * cycle.relative_change, 3)
              << " % per cycle)\n";
  else
    std::cout << "no cycle of " << channel << " after " << after_s << " s in the run at the edge\n";
  std::cout << "wrote " << std::filesystem::absolute(out_dir).string()
            << "/edge.json, edge_run.csv, edge.svg, report.md, case.json" << std::endl;
  return 0;
}

// Steady states and periodic orbits over one parameter (pseudo-arclength continuation from each Hopf point).
int Orbits(const std::string& file, const std::string& out_dir, const std::vector<std::string>& overrides,
           const std::string& continue_text) {
  if (continue_text.empty()) throw drillwave::InputError("--continue", "required: /json/pointer=first:last[:count]");
  const nlohmann::json doc = LoadCaseDocument(file, overrides);
  drillwave::io::OutputDirectory::CheckReplaceable(out_dir);
  const auto spec = drillwave::cases::ParseContinueOption(continue_text, doc);
  std::cout << "drillwave: steady states on " << spec.grid.size() << " values of " << spec.pointer
            << ", then periodic orbits from each Hopf point" << std::endl;
  const auto result = drillwave::cases::ContinueOrbits(doc, spec, [](int branch, int points, double p, double period) {
    if (points % 10 == 0)
      std::cout << "  branch " << branch << ": " << points << " orbits, now at " << drillwave::Significant(p, 6)
                << " (period " << drillwave::Significant(period, 5) << " s)" << std::endl;
  });
  drillwave::cases::WriteOrbitsOutputs(doc, spec, result, out_dir);
  std::cout << result.equilibria.hopf.size() << " Hopf point(s):";
  for (const auto& h : result.equilibria.hopf) std::cout << " " << drillwave::Significant(h.p, 8);
  std::cout << "\n";
  for (std::size_t b = 0; b < result.branches.size(); ++b) {
    std::cout << "branch " << b << ": " << result.branches[b].points.size() << " orbits, " << result.branches[b].end;
    for (const auto& f : result.branches[b].folds) std::cout << "; fold at " << drillwave::Significant(f.p, 8);
    std::cout << "\n";
  }
  for (const auto& [a, b] : drillwave::cases::CoexistenceRanges(result))
    std::cout << "stable steady state and stable periodic orbit coexist for " << spec.pointer << " in ["
              << drillwave::Significant(a, 6) << ", " << drillwave::Significant(b, 6) << "]\n";
  std::cout << "wall time " << drillwave::Significant(result.wall_time_s, 3) << " s\nwrote "
            << std::filesystem::absolute(out_dir).string() << "/orbits.csv, orbits.svg, report.md, case.json"
            << std::endl;
  return 0;
}

// compare-controllers' options as given (NaN, empty: not given, the library's defaults).
struct ControllersArguments {
  double handover_s = std::nan(""), after_s = std::nan(""), tuning_period_s = std::nan("");
  double torque_limit_Nm = std::nan("");
  std::string stiff_pi;                // "J,kp,ki"
  std::vector<std::string> envelope;   // two map axes
  std::string actuator_delays;         // "d1,d2,..."
};
std::optional<double> GivenOrNot(double v) { return std::isnan(v) ? std::nullopt : std::optional<double>(v); }

// --actuator-delays: delays [s] in [0, 10] (the top's actuator_delay_s range); none if not given.
std::vector<double> ActuatorDelays(const std::string& text) {
  if (text.empty()) return {};
  const std::vector<double> delays = drillwave::cases::ParseSweepValues(text, "actuator_delays");
  for (double d : delays)
    if (!(d >= 0 && d <= 10))
      throw drillwave::InputError("--actuator-delays", "expected delays in [0, 10] s, got " +
                                                           drillwave::Significant(d, 6) + " in '" + text + "'");
  return delays;
}

void PrintLaws(const drillwave::cases::ControllerComparison& c) {
  for (const auto& r : c.laws) {
    std::cout << "  " << r.law << ": " << r.verdict << " (rightmost Re s " << drillwave::Significant(r.rightmost_re, 4)
              << " 1/s), ";
    if (!r.run_failure.empty()) {
      std::cout << "the run blew up: " << r.run_failure << std::endl;
      continue;
    }
    const std::string suppression =
        r.suppressed_after_s ? "stick-slip suppressed after " + drillwave::Significant(*r.suppressed_after_s, 3) + " s"
                             : std::string("not suppressed");
    std::cout << "severity " << drillwave::Significant(r.severity, 3) << ", top torque std "
              << drillwave::Significant(r.torque_std_Nm, 4) << " N m (reduction "
              << drillwave::Significant(r.torque_reduction_pct, 3) << " %), " << suppression << std::endl;
  }
}

// The case's string under each top-drive law, each taking over at the same instant of the stiff PI's stick-slip.
int CompareControllers(const std::string& file, const std::string& out_dir, const std::vector<std::string>& overrides,
                       const ControllersArguments& args, int jobs) {
  const nlohmann::json doc = LoadCaseDocument(file, overrides);
  drillwave::cases::ControllerComparisonSpec spec;
  spec.handover_s = GivenOrNot(args.handover_s);
  spec.after_s = GivenOrNot(args.after_s).value_or(spec.after_s);
  spec.tuning_period_s = GivenOrNot(args.tuning_period_s);
  if (spec.tuning_period_s && !(*spec.tuning_period_s > 0))
    throw drillwave::InputError("--tuning-period",
                                "expected a period > 0 s, got " + drillwave::Significant(args.tuning_period_s, 6));
  if (!args.stiff_pi.empty()) {
    const std::vector<double> v = drillwave::cases::ParseSweepValues(args.stiff_pi, "stiff_pi");
    if (v.size() != 3)
      throw drillwave::InputError("--stiff-pi", "expected J,kp,ki (three numbers), got " + args.stiff_pi);
    spec.stiff_pi = drillwave::cases::StiffPi{v[0], v[1], v[2]};
  }
  if (!std::isnan(args.torque_limit_Nm)) {
    if (!(args.torque_limit_Nm > 0) || !std::isfinite(args.torque_limit_Nm))
      throw drillwave::InputError("--torque-limit", "expected a torque > 0 N m, got " +
                                                        drillwave::Significant(args.torque_limit_Nm, 6));
    spec.torque_limit_Nm = args.torque_limit_Nm;
  }
  const std::vector<double> delays = ActuatorDelays(args.actuator_delays);
  if (jobs < 1) throw drillwave::InputError("-j", "expected a whole number >= 1, got " + std::to_string(jobs));
  drillwave::cases::ControllerComparison c;
  std::optional<std::pair<drillwave::cases::MapAxis, drillwave::cases::MapAxis>> envelope;
  try {
    if (!args.envelope.empty()) {  // the axes address the laws' cases, checked on the stiff PI's before any run
      if (args.envelope.size() != 2)
        throw drillwave::InputError("--envelope", "expected two axes, POINTER1=first:last:n POINTER2=first:last:n");
      const nlohmann::json stiff = drillwave::cases::StiffPiCase(doc, spec);
      envelope.emplace(drillwave::cases::ParseMapAxis(args.envelope[0], stiff, "envelope"),
                       drillwave::cases::ParseMapAxis(args.envelope[1], stiff, "envelope"));
    }
    if (!delays.empty())  // every law again at each delay: five runs a delay, estimated on the stiff PI's case
      drillwave::cases::CheckPointsWork(drillwave::cases::ParseCase(drillwave::cases::StiffPiCase(doc, spec)),
                                        5.0 * static_cast<double>(delays.size()), true, "actuator_delays");
    drillwave::io::OutputDirectory::CheckReplaceable(out_dir);
    std::cout << "drillwave: top-drive laws on '" << doc.value("name", std::string("case")) << "' (stiff PI, "
              << "SoftSpeed, Z-Torque, wave cancellation, filtered), each from the same stick-slip" << std::endl;
    c = drillwave::cases::CompareControllers(doc, spec);
  } catch (const drillwave::InputError& e) {  // the spec's fields are this command's options
    const std::string& field = e.json_path();
    const std::string option = field == "handover_s" ? "--handover" : field == "after_s" ? "--after"
                               : field == "tuning_period_s" ? "--tuning-period" : "";
    if (option.empty()) throw;
    throw drillwave::InputError(option, std::string(e.what()).substr(field.size() + 2));
  }
  PrintLaws(c);
  drillwave::cases::ControllerStudies studies;
  std::optional<drillwave::cases::ControllerEnvelopes> envelopes;
  if (envelope) {
    std::cout << "envelopes: " << envelope->first.values.size() << " x " << envelope->second.values.size()
              << " grid points per law, each analysed and run" << std::endl;
    envelopes = drillwave::cases::MapControllerEnvelopes(c, envelope->first, envelope->second, jobs);
    for (const auto& e : envelopes->laws)
      std::cout << "  " << e.law << ": free of stick-slip at " << e.linear_free << " points by the linear verdict, "
                << e.simulated_free << " by simulation; simulation agrees at " << e.boundary_agreeing << " of "
                << e.boundary << " boundary points, " << e.simulated_boundary << " on the runs' own boundary ("
                << drillwave::Significant(e.map.linear_wall_time_s, 3)
                << " s linear, " << drillwave::Significant(e.map.simulation_wall_time_s, 3) << " s runs)"
                << std::endl;
    studies.envelopes = &*envelopes;
  }
  if (!delays.empty()) {
    std::cout << "actuator delays: every law at " << args.actuator_delays << " s" << std::endl;
    studies.delays = drillwave::cases::CompareUnderActuatorDelays(doc, spec, c, delays);
    for (const auto& at_delay : studies.delays) {
      std::cout << "  delay " << drillwave::Significant(at_delay.actuator_delay_s, 3) << " s:" << std::endl;
      PrintLaws(at_delay);
    }
  }
  drillwave::cases::WriteControllerComparison(doc, c, out_dir, studies);
  std::cout << "wrote " << std::filesystem::absolute(out_dir).string()
            << "/controllers.csv, controllers.md, controllers.svg, case.json"
            << (envelope ? ", envelopes.csv, envelopes.svg" : "") << (delays.empty() ? "" : ", delays.csv")
            << std::endl;
  return 0;
}

// The arguments several commands share: a case, its --set overrides, a recording with its channel map, sidecar and
// window, and how many things run at once.
struct CommonArguments {
  std::string case_file, recording_file, sidecar_file, window;
  std::vector<std::string> overrides, maps;
  int jobs = drillwave::DefaultThreadCount();  // the CPUs this process may run on (taskset, cpusets)
};

// A command's own arguments and its output folder, shared between its options and its action.
template <class Arguments>
struct ArgumentsAndOutput {
  Arguments args;
  std::string out;
};
template <class Arguments>
std::shared_ptr<ArgumentsAndOutput<Arguments>> WithOutput(const std::string& default_out) {
  return std::make_shared<ArgumentsAndOutput<Arguments>>(ArgumentsAndOutput<Arguments>{Arguments{}, default_out});
}

// A subcommand and what it does once its arguments are parsed.
struct Command {
  CLI::App* app;
  std::function<int()> run;
};

Command AddRun(CLI::App& app, CommonArguments& common) {
  struct Arguments {
    std::string out = "drillwave-out";
    bool check = false;
  };
  auto a = std::make_shared<Arguments>();
  auto* run = app.add_subcommand("run", "run a case and write trajectory.csv, summary.json, plot.svg, report.md");
  run->add_option("case", common.case_file, "case JSON file (default: the embedded default case)");
  run->add_option("--out,-o", a->out, "output folder (written all or nothing)");
  run->add_option("--set", common.overrides,
                  "override a parameter by JSON pointer, e.g. --set /model/bit/inertia_kgm2=120");
  run->add_flag("--check", a->check, "exit with 1 if an expectation of the case fails");
  return {run, [a, &common] { return RunAndWrite(common.case_file, a->out, common.overrides, a->check); }};
}

Command AddValidate(CLI::App& app, CommonArguments& common) {
  auto* validate = app.add_subcommand("validate", "check a case file without running it");
  validate->add_option("case", common.case_file, "case JSON file")->required();
  validate->add_option("--set", common.overrides, "override a parameter by JSON pointer");
  return {validate, [&common] {
            const Case c = drillwave::cases::ParseCase(LoadCaseDocument(common.case_file, common.overrides));
            std::cout << "case '" << c.name << "' is valid (kind " << c.kind << ")\n";
            return 0;
          }};
}

Command AddSweep(CLI::App& app, CommonArguments& common) {
  struct Arguments {
    std::string pointer, values, out = "drillwave-sweep";
  };
  auto a = std::make_shared<Arguments>();
  auto* sweep = app.add_subcommand(
      "sweep",
      "run a case once for each value of one parameter (independent runs in parallel): sweep.csv with every "
      "summary statistic per value, bifurcation.svg, report.md");
  sweep->add_option("case", common.case_file, "case JSON file (default: the embedded default case)");
  sweep->add_option("--param,-p", a->pointer, "the parameter's JSON pointer, e.g. /model/upper_disc/input_voltage_V")
      ->required();
  sweep->add_option("--values,-v", a->values, "first:last:count (evenly spaced) or v1,v2,...")->required();
  sweep->add_option("--jobs,-j", common.jobs, "runs at once (default: the CPUs this process may run on)");
  sweep->add_option("--out,-o", a->out, "output folder (written all or nothing)");
  sweep->add_option("--set", common.overrides, "override another parameter by JSON pointer");
  return {sweep, [a, &common] {
            return Sweep(common.case_file, a->out, common.overrides, a->pointer, a->values, common.jobs);
          }};
}

Command AddOrbits(CLI::App& app, CommonArguments& common) {
  struct Arguments {
    std::string out = "drillwave-orbits", range, edge, channel = "bit_rpm";
    double after = 0, tolerance = 1e-12;
  };
  auto a = std::make_shared<Arguments>();
  auto* orbits = app.add_subcommand(
      "orbits",
      "steady states and periodic orbits over one parameter: Hopf points, branches of periodic orbits by "
      "pseudo-arclength continuation with Floquet multipliers (saltation matrices at stick/slip), folds");
  orbits->add_option("case", common.case_file, "case JSON file (default: the embedded default case)");
  auto* continue_option =
      orbits->add_option("--continue", a->range, "/json/pointer=first:last[:count], the parameter and its range");
  orbits
      ->add_option("--edge", a->edge,
                   "instead of --continue, for any kind: POINTER=decays:sticks, a perturbation's parameter with a "
                   "value whose run decays to the steady state and one whose run sticks; bisection finds the "
                   "boundary between the attractors and the saddle cycle the run at it shadows")
      ->excludes(continue_option);
  orbits->add_option("--channel", a->channel, "with --edge: the channel whose cycle is measured (default bit_rpm)");
  orbits->add_option("--after", a->after, "with --edge: look for the cycle after this time [s] (the perturbation's)");
  orbits->add_option("--tolerance", a->tolerance,
                     "with --edge: relative width of the final bracket (default 1e-12: the closer, the longer the run "
                     "shadows the cycle)");
  orbits->add_option("--out,-o", a->out, "output folder (written all or nothing)");
  orbits->add_option("--set", common.overrides, "override another parameter by JSON pointer");
  return {orbits, [a, &common] {
            if (!a->edge.empty())
              return EdgeOrbit(common.case_file, a->out, common.overrides, a->edge, a->channel, a->after, a->tolerance);
            if (a->range.empty())
              throw drillwave::InputError("--continue", "required: /json/pointer=first:last[:count] (or --edge)");
            return Orbits(common.case_file, a->out, common.overrides, a->range);
          }};
}

Command AddStability(CLI::App& app, CommonArguments& common) {
  struct Arguments {
    std::string out = "drillwave-stability", pointer, values, draws;
    std::vector<std::string> map_axes;
    bool simulate = false, full_spectrum = false, no_run = false;
    int draw_count = 50;
  };
  auto a = std::make_shared<Arguments>();
  auto* stability =
      app.add_subcommand("stability",
                         "steady states at the inputs' final values and the characteristic roots of the linearization "
                         "about each; with --param, a stability map over that parameter");
  stability->add_option("case", common.case_file, "case JSON file (default: the embedded default case)");
  stability->add_option("--param,-p", a->pointer, "map over this parameter (JSON pointer)");
  stability->add_option("--values,-v", a->values, "first:last:count or v1,v2,... (with --param)");
  stability
      ->add_option("--map", a->map_axes,
                   "two-parameter map: POINTER1=first:last:n POINTER2=first:last:n (stability_map.csv/.svg)")
      ->expected(2);
  stability->add_flag("--simulate", a->simulate,
                      "with --map: also run the case at every grid point and mark "
                      "the regime it reaches (stick-slip, smooth, bit bouncing)");
  stability->add_option("--draws", a->draws,
                        "with --map: a CSV of parameter draws (columns named by JSON pointers, e.g. calibrate's "
                        "posterior_samples.csv): the map for each, and per point the probability of stick-slip "
                        "(p_linearly_unstable, p_stick_slip with --simulate; p_stick_slip.svg)");
  stability->add_option("--draw-count", a->draw_count,
                        "with --draws: this many rows spread evenly over the file (default 50, 0: every row)");
  stability->add_flag("--full-spectrum", a->full_spectrum,
                      "with --map: every point's full spectrum (the reference) instead of roots continued from the "
                      "neighbouring point and certified by the argument principle");
  stability->add_flag("--no-run", a->no_run,
                      "one case: do not run it from its start (by default it runs, to tell whether a stable steady "
                      "state coexists with a stick-slip cycle)");
  stability->add_option("--jobs,-j", common.jobs, "analyses at once (default: the CPUs this process may run on)");
  stability->add_option("--out,-o", a->out, "output folder (written all or nothing)");
  stability->add_option("--set", common.overrides, "override a parameter by JSON pointer");
  return {stability, [a, &common] {
            if (!a->map_axes.empty()) {
              if (!a->pointer.empty()) throw drillwave::InputError("--map", "give either --map or --param, not both");
              return StabilityMap2D(common.case_file, a->out, common.overrides, a->map_axes, a->simulate,
                                    a->full_spectrum, common.jobs, a->draws, a->draw_count);
            }
            if (a->simulate) throw drillwave::InputError("--simulate", "only with --map");
            if (!a->draws.empty()) throw drillwave::InputError("--draws", "only with --map");
            if (a->pointer.empty() != a->values.empty())
              throw drillwave::InputError("--param/--values", "a stability map needs both --param and --values");
            return Stability(common.case_file, a->out, common.overrides, a->pointer, a->values, common.jobs,
                             !a->no_run);
          }};
}

Command AddInspect(CLI::App& app, CommonArguments& common) {
  struct Arguments {
    std::string out = "drillwave-inspect", bit = "bit_rpm", top = "top_rpm";
  };
  auto a = std::make_shared<Arguments>();
  auto* inspect = app.add_subcommand(
      "inspect",
      "first look at a recording (CSV with time_s): artefacts flagged and masked, stuck episodes of the "
      "bit, stretches without sticking, stick-slip period, top-speed steadiness, correlated channels");
  inspect->add_option("recording", common.recording_file, "recording CSV file")->required();
  inspect->add_option("--bit", a->bit, "the bit speed channel (default bit_rpm)");
  inspect->add_option("--top", a->top, "the top speed channel (default top_rpm)");
  inspect->add_option("--out,-o", a->out, "output folder (written all or nothing)");
  return {inspect, [a, &common] { return Inspect(common.recording_file, a->out, a->bit, a->top); }};
}

Command AddCompare(CLI::App& app, CommonArguments& common) {
  struct Arguments {
    std::string out = "drillwave-compare";
  };
  auto a = std::make_shared<Arguments>();
  auto* compare =
      app.add_subcommand("compare",
                         "run a case and compare it with a recording: features side by side (periods, stick fraction, "
                         "speed levels, top-drive stiffness) and point-by-point residuals");
  compare->add_option("case", common.case_file, "case JSON file")->required();
  compare->add_option("recording", common.recording_file, "recording CSV file (time_s and channels)")->required();
  compare->add_option("--map", common.maps,
                      "recording_channel=model_channel[*scale], e.g. tob_Nm=bit_torque_Nm; channels "
                      "not mapped are compared with the model channel of the same name");
  compare->add_option("--window", common.window, "begin,end [s] of the comparison (default: all both cover)");
  compare->add_option("--sidecar", common.sidecar_file,
                      "a synthetic recording's operator sidecar (as for diagnose): the model "
                      "runs its 30 s warm-up first and is compared in recording time");
  compare->add_option("--out,-o", a->out, "output folder (written all or nothing)");
  compare->add_option("--set", common.overrides, "override a parameter of the case by JSON pointer");
  return {compare, [a, &common] {
            return Compare(common.case_file, common.recording_file, common.sidecar_file, common.overrides, common.maps,
                           common.window, a->out);
          }};
}

Command AddFit(CLI::App& app, CommonArguments& common) {
  struct Arguments {
    std::vector<std::string> params, features;
    int max_evaluations = 200;
    std::string out = "drillwave-fit";
  };
  auto a = std::make_shared<Arguments>();
  auto* fit = app.add_subcommand(
      "fit",
      "fit parameters of a case (by JSON pointer, with bounds) so that its features match a recording's "
      "(bounded derivative-free search, NLopt Subplex; writes the fitted case)");
  fit->add_option("case", common.case_file, "case JSON file")->required();
  fit->add_option("recording", common.recording_file, "recording CSV file")->required();
  fit->add_option("--param,-p", a->params, "/json/pointer:lower:upper (repeat for several)")->required();
  fit->add_option("--feature", a->features,
                  "a feature to match (repeat; default: bit_oscillation_period_s, "
                  "stick_fraction, bit_speed_mean, bit_speed_max)");
  fit->add_option("--map", common.maps, "recording_channel=model_channel[*scale]");
  fit->add_option("--sidecar", common.sidecar_file, "a synthetic recording's operator sidecar (as for diagnose)");
  fit->add_option("--window", common.window, "begin,end [s]");
  fit->add_option("--max-evaluations", a->max_evaluations, "model runs at most (default 200)");
  fit->add_option("--out,-o", a->out, "output folder (written all or nothing)");
  fit->add_option("--set", common.overrides, "override a parameter of the case by JSON pointer");
  return {fit, [a, &common] {
            return Fit(common.case_file, common.recording_file, common.sidecar_file, common.overrides, common.maps,
                       common.window, a->params, a->features, a->max_evaluations, a->out);
          }};
}

Command AddDiagnose(CLI::App& app, CommonArguments& common) {
  const auto a = WithOutput<DiagnoseArguments>("drillwave-diagnose");
  auto* diagnose =
      app.add_subcommand("diagnose",
                         "name what a case leaves out of a recording, model it, refit and check on a held-out window: "
                         "evidence proposes effects, each is fitted (NLopt) and kept only if the held-out error falls");
  diagnose
      ->add_option("case", common.case_file,
                   "case JSON file (for the synthetic recordings: json-cases/baseline-60rpm.json)")
      ->required();
  diagnose->add_option("recording", common.recording_file, "recording CSV file")->required();
  diagnose->add_option("--sidecar", common.sidecar_file,
                       "the synthetic recording's operator sidecar (recNN.json): sets "
                       "depth, WOB and the rpm schedule, with a 30 s warm-up");
  diagnose->add_option("--map", common.maps, "recording_channel=model_channel[*scale]");
  diagnose->add_option("--fit-window", a->args.fit_window,
                       "begin,end [s] in recording time (default: the first half of the usable recording)");
  diagnose->add_option("--held-out", a->args.held_out, "begin,end [s] (default: the second half)");
  diagnose->add_option("--margin", a->args.margin,
                       "an effect is kept when the held-out error falls by at least this fraction (default 0.2)");
  diagnose->add_option("--evaluations", a->args.evaluations_per_parameter,
                       "model runs per fitted parameter and candidate (default 10)");
  diagnose->add_option("--fit-tolerance", a->args.fit_tolerance,
                       "the fits' runs use at most this tolerance's accuracy; candidates are judged at the case's "
                       "(default 1e-4; 0: the case's)");
  diagnose->add_option("--sample-window", a->args.sample_window_s,
                       "each recorded sample is the mean over this window [s] ending at it; the model's measured "
                       "channels are read the same way (default: the recording's sample interval; 0: point samples)");
  diagnose->add_option("--draws", a->args.draws,
                       "the baseline and each fitted candidate are judged over this many draws of the model's random "
                       "inputs (its seeds and the sensor noise's; default 5)");
  diagnose->add_option("-j,--jobs", a->args.threads, "candidates fitted in parallel (default 1)");
  diagnose->add_option("--predict-until", a->args.predict_until_s,
                       "run the fitted model on to this recording time [s], past the recording's end, and write its "
                       "channels to prediction.csv (from the fit window's start, without sensor noise)");
  diagnose->add_option("--out,-o", a->out, "output folder (written all or nothing)");
  diagnose->add_option("--set", common.overrides, "override a parameter of the case by JSON pointer");
  return {diagnose, [a, &common] {
            return Diagnose(common.case_file, common.recording_file, common.sidecar_file, common.overrides, common.maps,
                            a->args, a->out);
          }};
}

Command AddCalibrate(CLI::App& app, CommonArguments& common) {
  const auto a = WithOutput<CalibrateArguments>("drillwave-calibrate");
  auto* calibrate = app.add_subcommand(
      "calibrate",
      "the posterior of a case's parameters given a recording (the diagnosis loop's feature likelihood, "
      "an affine-invariant ensemble sampler): posterior_samples.csv, the held-out window's posterior "
      "predictive band and its coverage");
  calibrate->add_option("case", common.case_file, "case JSON file (e.g. diagnose's fitted-case.json)")->required();
  calibrate->add_option("recording", common.recording_file, "recording CSV file")->required();
  calibrate->add_option("--sidecar", common.sidecar_file, "a synthetic recording's operator sidecar (as for diagnose)");
  calibrate->add_option("--params", a->args.params, "/json/pointer:lower:upper (uniform prior), one or more")
      ->required();
  calibrate->add_option("--map", common.maps, "recording_channel=model_channel[*scale]");
  calibrate->add_option("--fit-window", a->args.fit_window, "begin,end [s] (default: as diagnose)");
  calibrate->add_option("--held-out", a->args.held_out, "begin,end [s] (default: as diagnose)");
  calibrate->add_option("--sample-window", a->args.sample_window_s,
                        "each recorded sample is the mean over this window [s] (default: the sample interval)");
  calibrate->add_option("--walkers", a->args.posterior.walkers, "ensemble walkers, even, >= 2 p + 2 (default 16)");
  calibrate->add_option("--steps", a->args.posterior.steps, "ensemble steps (default 60)");
  calibrate->add_option("--burn-in", a->args.posterior.burn_in, "first steps left out (default 20)");
  calibrate->add_option("--predictive-draws", a->args.posterior.predictive_draws,
                        "posterior samples run over the whole span for the predictive band (default 40, 0: none)");
  calibrate->add_option("--seed", a->args.posterior.seed, "random seed (default 1)");
  calibrate->add_option("-j,--jobs", a->args.posterior.threads, "walkers run at once (default 1)");
  calibrate->add_option("--out,-o", a->out, "output folder (written all or nothing)");
  calibrate->add_option("--set", common.overrides, "override a parameter of the case by JSON pointer");
  return {calibrate, [a, &common] {
            return Calibrate(common.case_file, common.recording_file, common.sidecar_file, common.overrides,
                             common.maps, a->args, a->out);
          }};
}

Command AddEstimate(CLI::App& app, CommonArguments& common) {
  auto a = std::make_shared<EstimateArguments>();
  auto* estimate = app.add_subcommand(
      "estimate",
      "a virtual downhole sensor: the bit's speed, torque, weight on bit and stuck flag estimated from "
      "surface channels only, scored against the recording's downhole channels where it has them");
  estimate
      ->add_option("case", common.case_file,
                   "case JSON file (two_mass or axial_torsional; e.g. diagnose's fitted-case.json)")
      ->required();
  estimate->add_option("recording", common.recording_file, "recording CSV file")->required();
  estimate->add_option("--sidecar", common.sidecar_file, "a synthetic recording's operator sidecar (as for diagnose)");
  estimate->add_option("--from", a->from, "surface channels, e.g. top_rpm,top_torque_kNm,hookload_kN")->required();
  estimate->add_option("--window", a->window, "begin,end [s] of the error figures (default: all)");
  estimate->add_option("--out,-o", a->out, "output folder (written all or nothing)");
  estimate->add_flag("--follow", a->follow,
                     "read the recording while it is written (a growing file, or - for standard input) and print "
                     "each estimate row to standard output as soon as the latency allows; the folder at the end");
  estimate
      ->add_option("--follow-idle", a->follow_idle_s,
                   "with --follow on a file: end after this many seconds without a new line (default 10)")
      ->check(CLI::PositiveNumber);
  estimate->add_option("--fuse", a->fuse,
                        "downhole telemetry channels fused into the estimate at their delay, e.g. bit_rpm,wob_kN: "
                        "their innovation low-passed corrects the model's slow error (not with --follow)");
  estimate->add_option("--fuse-delay", a->fusion.telemetry_delay_s,
                       "with --fuse: the telemetry's delay [s] (default: read from the bit speed channel)");
  estimate->add_option("--fuse-time-constant", a->fusion.innovation_time_constant_s,
                       "with --fuse: the innovation's low-pass time constant [s] (default 20)");
  estimate->add_option("--set", common.overrides, "override a parameter of the case by JSON pointer");
  return {estimate, [a, &common, estimate] {
            a->read_fuse_delay = estimate->count("--fuse-delay") == 0;
            if (!a->fuse.empty() && a->follow)
              throw drillwave::ParameterError("fuse", "telemetry is fused on a whole recording, not with --follow");
            return Estimate(common.case_file, common.recording_file, common.sidecar_file, common.overrides, *a);
          }};
}

Command AddCompareControllers(CLI::App& app, CommonArguments& common) {
  const auto a = WithOutput<ControllersArguments>("drillwave-controllers");
  auto* controllers =
      app.add_subcommand("compare-controllers",
                         "run a case's string under each top-drive law against stick-slip (the stiff PI as given, "
                         "SoftSpeed tuned to its stick-slip period, Z-Torque matched to the pipe, the arriving "
                         "wave cancelled), each taking "
                         "over at the same instant of the stiff PI's stick-slip: controllers.csv, controllers.md "
                         "(verdict, severity, torque fluctuation, time to suppress), controllers.svg; with "
                         "--envelope each law's stick-slip-free region, with --actuator-delays each law under "
                         "delay");
  controllers->add_option("case", common.case_file, "case JSON file with a PI top drive (or give --stiff-pi)")
      ->required();
  controllers->add_option("--handover", a->args.handover_s,
                          "when the laws take over [s] (default: the start of the case's statistics window)");
  controllers->add_option("--after", a->args.after_s, "the runs end this long after it [s] (default 60, >= 20)");
  controllers->add_option("--tuning-period", a->args.tuning_period_s,
                          "SoftSpeed's stick-slip period [s] (default: the stiff PI's after the handover)");
  controllers->add_option("--stiff-pi", a->args.stiff_pi,
                          "J,kp,ki: the stiff PI top drive (inertia, gains) replacing the case's top (needed for a "
                          "top that is not a PI top drive, e.g. dissipative)");
  controllers
      ->add_option("--envelope", a->args.envelope,
                   "POINTER1=first:last:n POINTER2=first:last:n: each law, tuned at the case's point, mapped "
                   "over the grid (linear verdict and a run per point): envelopes.csv, envelopes.svg")
      ->expected(2);
  controllers->add_option("--actuator-delays", a->args.actuator_delays,
                          "d1,d2,... [s]: every law again with each actuator delay of the drive (delays.csv)");
  controllers->add_option("--torque-limit", a->args.torque_limit_Nm,
                          "the drive's torque limit [N m] > 0 for every law and run");
  controllers->add_option("--jobs,-j", common.jobs,
                          "envelope points at once (default: the CPUs this process may run on)");
  controllers->add_option("--out,-o", a->out, "output folder (written all or nothing)");
  controllers->add_option("--set", common.overrides, "override a parameter of the case by JSON pointer");
  return {controllers, [a, &common] {
            return CompareControllers(common.case_file, a->out, common.overrides, a->args, common.jobs);
          }};
}

Command AddKinds(CLI::App& app) {
  return {app.add_subcommand("kinds", "list the model kinds with their fields, units and ranges"),
          [] { return ListKinds(); }};
}

}  // namespace

int main(int argc, char** argv) {
  drillwave::io::InstallTerminationCleanup();  // before any thread exists: SIGTERM/SIGINT remove unfinished outputs
  // Long work (a many-section string's roots, a huge recording) says how far it is on stderr every 5 s
  // (DRILLWAVE_PROGRESS_S: another interval; 0: never).
  {
    const char* every = std::getenv("DRILLWAVE_PROGRESS_S");
    const double interval = every && *every ? std::strtod(every, nullptr) : 5.0;
    if (interval > 0 && std::isfinite(interval))
      drillwave::SetProgressSink([](const std::string& line) { std::cerr << "drillwave: " << line << std::endl; },
                                 interval);
  }
  CLI::App app{"drillwave: drill-string vibration simulation (d'Alembert wave networks, delay equations)"};
  app.set_version_flag("--version", std::string("drillwave ") + DRILLWAVE_VERSION, "print the version and exit");
  app.require_subcommand(0, 1);
  app.fallthrough();  // options of the tool (--max-samples) may follow the subcommand
  double max_samples = drillwave::cases::MaxSamples();
  app.add_option("--max-samples", max_samples,
                 "refuse cases asking for more output samples (duration / output_interval_s) or integration steps "
                 "(duration / max_step_s) than this (default 1e7)");
  CommonArguments common;
  const Command run = AddRun(app, common);
  const std::vector<Command> commands{
      AddValidate(app, common), AddSweep(app, common),    AddOrbits(app, common),
      AddStability(app, common), AddInspect(app, common),  AddCompare(app, common),
      AddFit(app, common),       AddDiagnose(app, common), AddCalibrate(app, common),
      AddEstimate(app, common),  AddCompareControllers(app, common), AddKinds(app)};

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // Bad options are bad input: exit 2 like every other, not CLI11's own codes.
    std::cerr << "drillwave: bad input: " << e.what() << " (see drillwave --help)" << std::endl;
    return 2;
  }
  try {
    drillwave::cases::SetMaxSamples(max_samples);
    // An argument given as "" is an error, never the same as leaving it out (which may mean the default case).
    for (CLI::App* sub : app.get_subcommands())
      for (const CLI::Option* option : sub->get_options())
        if (option->count() > 0 && option->get_type_size() != 0)
          for (const std::string& value : option->as<std::vector<std::string>>())
            if (value.empty())
              throw drillwave::InputError(option->get_name(), "empty value; expected " +
                                                                  std::string(option->get_description().empty()
                                                                                  ? "a value"
                                                                                  : option->get_description()));
    for (const Command& command : commands)
      if (command.app->parsed()) return command.run();
    return run.run();  // `run`, or no command: the embedded default case
  } catch (const drillwave::InputError& e) {
    std::cerr << "drillwave: bad input: " << InTermsOfFlags(e) << std::endl;
    return 2;
  } catch (const drillwave::NumericalError& e) {
    std::cerr << "drillwave: numerical failure: " << e.what() << std::endl;
    return 3;
  } catch (const drillwave::io::OutputError& e) {
    std::cerr << "drillwave: cannot write the outputs: " << e.what() << std::endl;
    return 5;
  } catch (const drillwave::MemoryError& e) {
    std::cerr << "drillwave: not enough memory: " << e.what() << std::endl;
    return 6;
  } catch (const std::bad_alloc&) {  // the machine's limit, met during the work: not a bug of drillwave's
    std::cerr << "drillwave: not enough memory: an allocation failed during the work (the machine's memory or this "
                 "process's address-space limit, ulimit -v, is exhausted); ask for less work (fewer samples, points or "
                 "runs) or free memory"
              << std::endl;
    return 6;
  } catch (const std::exception& e) {
    std::cerr << "drillwave: internal error: " << e.what() << std::endl;
    return 4;
  } catch (...) {
    std::cerr << "drillwave: internal error: an exception of unknown type" << std::endl;
    return 4;
  }
}
