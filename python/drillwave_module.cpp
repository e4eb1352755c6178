// drillwave's Python module: the library's run, sweep, stability and diagnose on a case given as a file, a dict or
// None (the embedded default case), with --set-style overrides; results as dicts, channels as NumPy arrays.
// Errors: the library's InputError becomes drillwave.InputError (a ValueError, with .path), its NumericalError
// drillwave.NumericalError (a RuntimeError, with .time and .state); the messages are the command line's.
// The arguments are read with the GIL held, the library's work runs without it (WithoutGil), and the results become
// Python objects with it again: other Python threads, and other drillwave calls, run meanwhile (issue 37).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <future>
#include <limits>
#include <map>
#include <mutex>
#include <optional>
#include <shared_mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <nlohmann/json.hpp>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/cases/model_kind.hpp"
#include "drillwave/cases/stability.hpp"
#include "drillwave/cases/sweep.hpp"
#include "drillwave/core/cancellation.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/parallel.hpp"
#include "drillwave/core/validity.hpp"
#include "drillwave/diagnosis/comparison.hpp"
#include "drillwave/diagnosis/fit.hpp"
#include "drillwave/diagnosis/loop.hpp"
#include "drillwave/diagnosis/posterior.hpp"
#include "drillwave/diagnosis/sidecar.hpp"
#include "drillwave/estimation/estimate.hpp"
#include "drillwave/estimation/recording_estimate.hpp"
#include "drillwave/io/json_reader.hpp"

namespace py = pybind11;
using drillwave::InputError;
using drillwave::ParameterError;
using nlohmann::json;

namespace {

constexpr int kMaxDepth = 64;  // as io::ParseJsonText allows a case file

// A Python value as JSON: dict (string keys), list, tuple, str, bool, int, float, None, and NumPy scalars and arrays
// (through their tolist()). Anything else is an InputError naming where in the value it is.
json ToJson(py::handle value, const std::string& path, int depth = 0) {
  const std::string where = path.empty() ? "/" : path;
  if (depth > kMaxDepth) throw InputError(where, "nested deeper than 64 levels");
  if (value.is_none()) return nullptr;
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  if (py::isinstance<py::int_>(value)) {
    const long long i = PyLong_AsLongLong(value.ptr());
    if (!(i == -1 && PyErr_Occurred())) return i;
    PyErr_Clear();  // beyond 64 bits: as a double (inf beyond that), which the readers judge with the field's range
    const double d = PyLong_AsDouble(value.ptr());
    if (d == -1 && PyErr_Occurred()) {
      PyErr_Clear();
      return value.attr("__gt__")(0).cast<bool>() ? std::numeric_limits<double>::infinity()
                                                  : -std::numeric_limits<double>::infinity();
    }
    return d;
  }
  if (py::isinstance<py::float_>(value)) return value.cast<double>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::dict>(value)) {
    json object = json::object();
    for (const auto& [key, item] : py::reinterpret_borrow<py::dict>(value)) {
      if (!py::isinstance<py::str>(key))
        throw InputError(where, "the key " + drillwave::ReadableText(py::repr(key).cast<std::string>()) +
                                    " is not a string; keys must be strings");
      const std::string name = key.cast<std::string>();
      object[name] = ToJson(item, path + "/" + name, depth + 1);
    }
    return object;
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    json array = json::array();
    std::size_t i = 0;
    for (const auto& item : value) array.push_back(ToJson(item, path + "/" + std::to_string(i++), depth + 1));
    return array;
  }
  if (py::hasattr(value, "tolist") && !py::isinstance<py::bytes>(value))  // NumPy: np.float32(2), np.array([0, 5])
    return ToJson(value.attr("tolist")(), path, depth);
  throw InputError(where, "a value of Python type " + std::string(py::str(py::type::of(value).attr("__name__"))) +
                              "; expected a dict, list, str, number, bool or None");
}

py::object FromJson(const json& value) {
  switch (value.type()) {
    case json::value_t::null: return py::none();
    case json::value_t::boolean: return py::bool_(value.get<bool>());
    case json::value_t::number_integer: return py::int_(value.get<long long>());
    case json::value_t::number_unsigned: return py::int_(value.get<unsigned long long>());
    case json::value_t::number_float: return py::float_(value.get<double>());
    case json::value_t::string: return py::str(value.get<std::string>());
    case json::value_t::array: {
      py::list list;
      for (const json& item : value) list.append(FromJson(item));
      return std::move(list);
    }
    case json::value_t::object: {
      py::dict dict;
      for (const auto& [key, item] : value.items()) dict[py::str(key)] = FromJson(item);
      return std::move(dict);
    }
    default: return py::none();  // binary and discarded values never occur in drillwave's documents
  }
}

py::array_t<double> ToArray(const std::vector<double>& values) {
  return py::array_t<double>(static_cast<py::ssize_t>(values.size()), values.data());
}

// A file name (str or os.PathLike) as a string; `what` names the argument in the error.
std::string FileName(py::handle file, const std::string& what) {
  if (!py::isinstance<py::str>(file) && !py::hasattr(file, "__fspath__"))
    throw InputError(what, "expected a file name (str or os.PathLike), got a value of type " +
                               std::string(py::str(py::type::of(file).attr("__name__"))));
  std::string name = py::str(py::module_::import("os").attr("fspath")(file)).cast<std::string>();
  // A C file name ends at its first NUL byte: the shorter name would be read instead (issue 41).
  if (const std::size_t nul = name.find('\0'); nul != std::string::npos)
    throw InputError(what, "the file name " + drillwave::ReadableText(name, 200) + " holds a NUL byte (at offset " +
                               std::to_string(nul) + "); a file name cannot contain one");
  return name;
}

// The case document: a file, a dict or None (the embedded default case), then the overrides: a dict
// {"/json/pointer": value} or a list of "/json/pointer=value" strings (the command line's --set).
json CaseDocument(py::handle case_, py::handle overrides) {
  json doc;
  if (case_.is_none())
    doc = drillwave::io::ParseJsonText(drillwave::cases::DefaultCaseText(), "the default case");
  else if (py::isinstance<py::dict>(case_))
    doc = ToJson(case_, "");
  else
    doc = drillwave::io::LoadJsonFile(FileName(case_, "case"));
  if (overrides.is_none()) return doc;
  if (py::isinstance<py::dict>(overrides)) {
    for (const auto& [key, value] : py::reinterpret_borrow<py::dict>(overrides)) {
      if (!py::isinstance<py::str>(key))
        throw InputError("set", "the key " + drillwave::ReadableText(py::repr(key).cast<std::string>()) +
                                    " is not a string; expected a JSON pointer such as /simulation/duration_s");
      const std::string pointer = key.cast<std::string>();
      drillwave::io::SetByPointer(doc, pointer, ToJson(value, pointer));
    }
  } else if (py::isinstance<py::list>(overrides) || py::isinstance<py::tuple>(overrides)) {
    for (const auto& item : overrides) {
      if (!py::isinstance<py::str>(item))
        throw InputError("set", "expected \"/json/pointer=value\" strings, got " +
                                    drillwave::ReadableText(py::repr(item).cast<std::string>()));
      drillwave::io::ApplySetOption(doc, item.cast<std::string>());
    }
  } else {
    throw InputError("set", "expected a dict {\"/json/pointer\": value} or a list of \"/json/pointer=value\"");
  }
  return doc;
}

// max_samples as a number (nullopt: None, the process-wide limit as it is); InputError for anything but a number.
std::optional<double> SampleLimit(py::handle limit) {
  if (limit.is_none()) return std::nullopt;
  const json value = ToJson(limit, "max_samples");
  if (!value.is_number())
    throw ParameterError("max_samples", "expected a finite number >= 1, got " + drillwave::ReadableText(value.dump()));
  return value.get<double>();
}

// The library's sample limit is process-wide: a call with its own max_samples holds it alone for its length (and
// puts the previous limit back), calls without one share it.
std::shared_mutex sample_limit_mutex;

// work() on a thread of its own while this one, taking the GIL every 50 ms, lets Python run its signal handlers: on
// Ctrl-C (KeyboardInterrupt, or whatever exception a handler raises) the library's work is cancelled
// (core/cancellation.hpp: it stops at its next integration step or map item), joined, and the exception raised.
// Called without the GIL.
template <class Work>
auto Interruptible(Work&& work) -> decltype(work()) {
  auto done = std::async(std::launch::async, std::forward<Work>(work));
  while (done.wait_for(std::chrono::milliseconds(50)) != std::future_status::ready) {
    const py::gil_scoped_acquire acquire;
    if (PyErr_CheckSignals() != 0) {
      drillwave::RequestCancellation();
      done.wait();
      drillwave::ClearCancellation();
      throw py::error_already_set();
    }
  }
  return done.get();
}

// Runs work() without the GIL, under the sample limit `limit` (nullopt: the current one), and returns its result;
// interruptible by Ctrl-C. work() must not touch a Python object; nothing in the library calls back into Python (a
// callback would take the GIL again with py::gil_scoped_acquire). The limit's lock is taken without the GIL, so a
// call waiting for it never blocks one that holds it and needs the GIL to return. Exceptions reach pybind11 with the
// GIL held again.
template <class Work>
auto WithoutGil(std::optional<double> limit, Work&& work) -> decltype(work()) {
  const py::gil_scoped_release release;
  if (!limit) {
    const std::shared_lock<std::shared_mutex> shared(sample_limit_mutex);
    return Interruptible(work);
  }
  const std::unique_lock<std::shared_mutex> alone(sample_limit_mutex);
  struct Restore {
    double previous = drillwave::cases::MaxSamples();
    ~Restore() { drillwave::cases::SetMaxSamples(previous); }
  } const restore;
  drillwave::cases::SetMaxSamples(*limit);  // InputError unless a finite number >= 1
  return Interruptible(work);
}

int Jobs(py::handle jobs) {
  if (jobs.is_none()) return drillwave::DefaultThreadCount();  // the CPUs this process may run on
  const json n = ToJson(jobs, "jobs");
  if (!n.is_number_integer() || n.get<long long>() < 1 || n.get<long long>() > 1024)
    throw InputError("jobs", "expected a whole number in [1, 1024], got " + drillwave::ReadableText(n.dump()));
  return n.get<int>();
}

// A sweep's values: "first:last:count", "v1,v2,..." or a sequence of numbers.
std::vector<double> Values(py::handle values) {
  if (py::isinstance<py::str>(values)) return drillwave::cases::ParseSweepValues(values.cast<std::string>(), "values");
  const json list = ToJson(values, "values");
  if (!list.is_array() || list.empty())
    throw InputError("values", "expected \"first:last:count\", \"v1,v2,...\" or a non-empty sequence of numbers");
  std::vector<double> out;
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (!list[i].is_number() || !std::isfinite(list[i].get<double>()))
      throw InputError("values/" + std::to_string(i),
                       "expected a finite number, got " + (list[i].is_number()
                                                               ? drillwave::ReadableNumber(list[i].get<double>())
                                                               : drillwave::ReadableText(list[i].dump())));
    out.push_back(list[i].get<double>());
  }
  return out;
}

py::dict Run(const py::object& case_, const py::object& overrides, const py::object& max_samples) {
  const std::optional<double> limit = SampleLimit(max_samples);
  const json doc = CaseDocument(case_, overrides);
  drillwave::cases::Case c;
  drillwave::cases::CaseRun run;
  std::vector<drillwave::cases::ExpectationCheck> checks;
  WithoutGil(limit, [&] {
    c = drillwave::cases::ParseCase(doc);
    run = drillwave::cases::RunCase(c);
    drillwave::cases::AddLinearVerdict(c, run.summary);
    checks = drillwave::cases::CheckExpectations(c.expect, run.summary);
  });
  py::dict channels;
  channels["time_s"] = ToArray(run.result.time_s);
  for (const auto& ch : run.result.channels) channels[py::str(ch.name)] = ToArray(ch.values);
  py::list expectations;
  for (const auto& e : checks)
    expectations.append(py::dict(py::arg("key") = e.key, py::arg("passed") = e.passed, py::arg("detail") = e.detail));
  py::dict result;
  result["name"] = c.name;
  result["kind"] = c.kind;
  result["channels"] = channels;
  result["summary"] = FromJson(run.summary);
  result["expectations"] = expectations;
  result["case"] = FromJson(c.document);
  return result;
}

py::dict Sweep(const py::object& case_, const std::string& param, const py::object& values,
               const py::object& overrides, const py::object& jobs, const py::object& max_samples) {
  const std::optional<double> limit = SampleLimit(max_samples);
  const json doc = CaseDocument(case_, overrides);
  const drillwave::cases::SweepSpec spec{param, Values(values), Jobs(jobs)};
  const auto sweep = WithoutGil(limit, [&] { return drillwave::cases::RunSweep(doc, spec, nullptr); });
  py::list points;
  for (const auto& p : sweep.points)
    points.append(py::dict(py::arg("value") = p.value, py::arg("ok") = p.ok, py::arg("summary") = FromJson(p.summary),
                           py::arg("error") = p.error));
  py::dict result;
  result["param"] = param;
  result["points"] = points;
  result["wall_time_s"] = sweep.wall_time_s;
  return result;
}

py::dict Stability(const py::object& case_, const py::object& param, const py::object& values,
                   const py::object& overrides, const py::object& jobs, const py::object& max_samples) {
  const std::optional<double> limit = SampleLimit(max_samples);
  const json doc = CaseDocument(case_, overrides);
  if (param.is_none() != values.is_none())
    throw InputError("param/values", "a stability map needs both param and values");
  if (param.is_none()) {
    drillwave::cases::Case c;
    const json analysis = WithoutGil(limit, [&] {
      c = drillwave::cases::ParseCase(doc);
      return drillwave::cases::StabilityToJson(drillwave::cases::AnalyzeStability(c));
    });
    py::dict result = FromJson(analysis);
    result["name"] = c.name;
    result["kind"] = c.kind;
    return result;
  }
  const drillwave::cases::SweepSpec spec{param.cast<std::string>(), Values(values), Jobs(jobs)};
  py::list rows;
  for (const auto& r : WithoutGil(limit, [&] { return drillwave::cases::StabilityMap(doc, spec); }))
    rows.append(py::dict(py::arg("value") = r.value, py::arg("branch") = r.branch,
                         py::arg("speed_rad_s") = r.speed_rad_s, py::arg("spectral_abscissa") = r.spectral_abscissa,
                         py::arg("frequency_rad_s") = r.frequency_rad_s,
                         py::arg("essential_abscissa") = r.essential_abscissa, py::arg("stable") = r.stable));
  py::dict result;
  result["param"] = spec.pointer;
  result["rows"] = rows;
  return result;
}

// (begin, end) in seconds from a Python pair (as JSON); InputError naming `name` otherwise.
std::pair<double, double> WindowArgument(const json& w, const std::string& name) {
  if (!w.is_array() || w.size() != 2 || !w[0].is_number() || !w[1].is_number())
    throw InputError(name, "expected (begin, end) in seconds, got " + drillwave::ReadableText(w.dump()));
  const double begin = w[0].get<double>(), end = w[1].get<double>();
  if (!(end > begin))
    throw InputError(name, "(" + drillwave::ReadableNumber(begin) + ", " + drillwave::ReadableNumber(end) +
                               ") is empty or reversed; expected (begin, end) with begin < end");
  return {begin, end};
}

// A synthetic recording's operator sidecar, given as a file name or a dict; `source` names it in errors.
json SidecarDocument(const py::object& sidecar, std::string& source) {
  const bool dict = py::isinstance<py::dict>(sidecar);
  source = dict ? "sidecar" : FileName(sidecar, "sidecar");
  return dict ? ToJson(sidecar, "") : drillwave::io::LoadJsonFile(source);
}

// What diagnose and calibrate read alike, with the GIL: the case (a sidecar, file or dict, sets the operating point
// and a warm-up before the recording), the recording's file, the windows and channel maps as given.
struct LoopArguments {
  json doc, fit_given, held_out_given, maps_given;
  std::string recording_name;
  double warmup_s = 0;
};

LoopArguments ReadLoopArguments(const py::object& case_, const py::object& recording_file, const py::object& sidecar,
                                const py::object& overrides, const py::object& map_texts,
                                const py::object& fit_window, const py::object& held_out) {
  namespace dg = drillwave::diagnosis;
  LoopArguments a;
  a.doc = CaseDocument(case_, overrides);
  if (!sidecar.is_none()) {
    std::string source;
    const json given = SidecarDocument(sidecar, source);
    a.doc = dg::CaseFromSidecar(given, a.doc, dg::kSidecarWarmupS, source);
  }
  a.recording_name = FileName(recording_file, "recording");
  a.fit_given = fit_window.is_none() ? json() : ToJson(fit_window, "fit_window");
  a.held_out_given = held_out.is_none() ? json() : ToJson(held_out, "held_out");
  a.maps_given = map_texts.is_none() ? json::array() : ToJson(map_texts, "maps");
  a.warmup_s = sidecar.is_none() ? 0 : dg::kSidecarWarmupS;
  return a;
}

// Without the GIL: the recording loaded, the loop's options with those a call sets (`set_options`) checked
// (LoopOptions::IsValid), then the windows checked against the model's span and the channel maps resolved.
std::pair<drillwave::diagnosis::Recording, drillwave::diagnosis::LoopOptions> LoopInputs(
    const LoopArguments& a, const std::function<void(drillwave::diagnosis::LoopOptions&)>& set_options = nullptr) {
  namespace dg = drillwave::diagnosis;
  const drillwave::cases::Case c = drillwave::cases::ParseCase(a.doc);
  dg::Recording recording = dg::LoadRecording(a.recording_name);
  dg::LoopOptions o = dg::DefaultLoopOptions(c, recording, a.warmup_s);
  if (!a.fit_given.is_null()) std::tie(o.fit_begin_s, o.fit_end_s) = WindowArgument(a.fit_given, "fit_window");
  if (!a.held_out_given.is_null())
    std::tie(o.held_out_begin_s, o.held_out_end_s) = WindowArgument(a.held_out_given, "held_out");
  if (set_options) set_options(o);
  drillwave::ThrowIfInvalid(o);
  const double offset = o.model_time_offset_s;
  dg::CheckWindow(recording, -offset, c.settings.duration_s - offset, o.fit_begin_s, o.fit_end_s);
  dg::CheckWindow(recording, -offset, c.settings.duration_s - offset, o.held_out_begin_s, o.held_out_end_s);
  std::vector<std::string> texts;
  for (const json& m : a.maps_given.is_array() ? a.maps_given : json::array({nullptr})) {
    if (!m.is_string())
      throw InputError("maps", "expected a list of \"recording_channel=model_channel[*scale]\", got " +
                                   drillwave::ReadableText(a.maps_given.dump()));
    texts.push_back(m.get<std::string>());
  }
  o.maps = dg::ResolveChannelMaps(texts, recording, dg::ProbeChannels(c));
  return {std::move(recording), std::move(o)};
}

// As `drillwave diagnose`: the usable recording is split into a fit and a held-out window unless they are given.
py::dict Diagnose(const py::object& case_, const py::object& recording_file, const py::object& sidecar,
                  const py::object& overrides, const py::object& map_texts, const py::object& fit_window,
                  const py::object& held_out, double margin, const py::object& jobs, const py::object& max_samples) {
  namespace dg = drillwave::diagnosis;
  // The Python arguments first, with the GIL; then the work without it, checked in the command line's order.
  const std::optional<double> limit = SampleLimit(max_samples);
  const LoopArguments args =
      ReadLoopArguments(case_, recording_file, sidecar, overrides, map_texts, fit_window, held_out);
  const int threads = Jobs(jobs);
  const json result = WithoutGil(limit, [&] {
    const auto [recording, o] = LoopInputs(args, [&](dg::LoopOptions& given) {
      given.margin = margin;
      given.threads = threads;
    });
    const dg::DiagnosisLoop loop = dg::RunDiagnosisLoop(args.doc, recording, o);
    json out = dg::DiagnosisLoopToJson(loop);
    out["fitted_case"] = loop.fitted_document;
    return out;
  });
  return FromJson(result);
}

// As `drillwave estimate`: the bit seen from the surface channels named in from_channels, scored against the
// downhole channels the recording holds (read only for the errors).
py::dict Estimate(const py::object& case_, const py::object& recording_file, const std::string& from_channels,
                  const py::object& sidecar, const py::object& overrides, const py::object& window,
                  const std::string& fuse, const py::object& fuse_delay, double fuse_time_constant) {
  namespace es = drillwave::estimation;
  namespace dg = drillwave::diagnosis;
  json doc = CaseDocument(case_, overrides);
  double hook_force_N = 0;
  es::EstimateOptions options;
  if (!sidecar.is_none()) {
    std::string source;
    const json given = SidecarDocument(sidecar, source);
    doc = dg::CaseFromSidecar(given, doc, dg::kSidecarWarmupS, source);
    hook_force_N = 1000 * given.value("hookload_setpoint_kN", 0.0);
    options.model_time_offset_s = -dg::kSidecarWarmupS;
  }
  drillwave::ThrowIfInvalid(options);
  const std::string recording_name = FileName(recording_file, "recording");
  const json window_given = window.is_none() ? json() : ToJson(window, "window");
  es::TelemetryFusion fusion;
  fusion.innovation_time_constant_s = fuse_time_constant;
  if (!fuse_delay.is_none()) fusion.telemetry_delay_s = fuse_delay.cast<double>();
  const auto [summary, e] = WithoutGil(std::nullopt, [&] {
    drillwave::cases::ParseCase(doc);  // every field checked (InputError names its path)
    const es::EstimatorModel model = es::EstimatorModelFromCase(doc, hook_force_N);
    es::ScoreWindow score;
    if (!window_given.is_null()) std::tie(score.begin_s, score.end_s) = WindowArgument(window_given, "window");
    const dg::Recording recording = dg::LoadRecording(recording_name);
    const es::SurfaceSignals signals =
        es::SignalsFromRecording(recording, es::ParseSurfaceChannels(from_channels, recording));
    es::BitEstimate estimate = es::EstimateBit(model, signals, options);
    if (!fuse.empty()) es::FuseTelemetry(recording, fuse, fusion, fuse_delay.is_none(), estimate);
    return std::make_pair(es::EstimateSummary(recording, estimate, score), std::move(estimate));
  });
  auto rpm = [](std::vector<double> rad_s) {
    for (double& v : rad_s) v /= drillwave::kRadPerSecondPerRpm;
    return rad_s;
  };
  std::vector<double> stuck(e.stuck.begin(), e.stuck.end());
  py::dict channels;
  channels["time_s"] = ToArray(e.time_s);
  channels["bit_rpm"] = ToArray(rpm(e.bit_speed_rad_s));
  channels["bit_rpm_band"] = ToArray(rpm(e.bit_speed_band_rad_s));
  channels["bit_torque_Nm"] = ToArray(e.bit_torque_Nm);
  channels["bit_torque_Nm_band"] = ToArray(e.bit_torque_band_Nm);
  channels["wob_N"] = ToArray(e.wob_N);
  channels["wob_N_band"] = ToArray(e.wob_band_N);
  channels["bit_stuck"] = ToArray(stuck);
  py::dict out = FromJson(summary);
  out["channels"] = channels;
  return out;
}

// As `drillwave calibrate`: params ["/pointer:lower:upper", ...].
py::dict Calibrate(const py::object& case_, const py::object& recording_file, const py::object& params,
                   const py::object& sidecar, const py::object& overrides, const py::object& map_texts,
                   const py::object& fit_window, const py::object& held_out, int walkers, int steps, int burn_in,
                   int predictive_draws, unsigned seed, const py::object& jobs, const py::object& max_samples) {
  namespace dg = drillwave::diagnosis;
  const std::optional<double> limit = SampleLimit(max_samples);
  dg::PosteriorOptions p;
  p.walkers = walkers, p.steps = steps, p.burn_in = burn_in, p.predictive_draws = predictive_draws, p.seed = seed;
  p.threads = Jobs(jobs);
  drillwave::ThrowIfInvalid(p);
  const LoopArguments args =
      ReadLoopArguments(case_, recording_file, sidecar, overrides, map_texts, fit_window, held_out);
  const json params_given = ToJson(params, "params");
  const json result = WithoutGil(limit, [&] {
    std::vector<dg::FitParameter> parameters;
    for (const json& q : params_given.is_array() ? params_given : json::array({nullptr})) {
      if (!q.is_string())
        throw InputError("params", "expected a list of \"/pointer:lower:upper\", got " +
                                       drillwave::ReadableText(params_given.dump()));
      parameters.push_back(dg::ParseFitParameter(q.get<std::string>()));
    }
    const auto [recording, o] = LoopInputs(args);
    const dg::Posterior post = dg::SamplePosterior(args.doc, recording, o, parameters, p);
    json out = dg::PosteriorToJson(post, recording);
    json samples = json::array();  // after burn-in: [step, walker, log_likelihood, values...]
    for (int s = post.burn_in + 1; s <= post.steps; ++s)
      for (int w = 0; w < post.walkers; ++w) {
        json row = {s, w, post.log_likelihood[s][w]};
        for (double v : post.chain[s][w]) row.push_back(v);
        samples.push_back(row);
      }
    out["samples"] = samples;
    out["map_case"] = post.map_document;
    return out;
  });
  return FromJson(result);
}

py::object* input_error_type = nullptr;
py::object* numerical_error_type = nullptr;

// The keyword that sets a library parameter (ParameterError names it as the library does, an options field by its own
// name) where this module's differs: "map /model/x" -> "maps /model/x", "threads" -> "jobs".
std::string KeywordOf(const std::string& parameter) {
  static const std::map<std::string, std::string> keywords = {
      {"map", "maps"},
      {"from", "from_channels"},
      {"threads", "jobs"},
      {"fit_begin_s", "fit_window"},
      {"fit_end_s", "fit_window"},
      {"held_out_begin_s", "held_out"},
      {"held_out_end_s", "held_out"},
      {"telemetry_delay_s", "fuse_delay"},
      {"innovation_time_constant_s", "fuse_time_constant"}};
  const std::size_t space = parameter.find(' ');
  const auto keyword = keywords.find(parameter.substr(0, space));
  if (keyword == keywords.end()) return parameter;
  return keyword->second + (space == std::string::npos ? "" : parameter.substr(space));
}

// drillwave.InputError(message) with .path (a bad parameter: its keyword), drillwave.NumericalError(message) with .time
// and .state.
void TranslateErrors(std::exception_ptr p) {
  try {
    if (p) std::rethrow_exception(p);
  } catch (const ParameterError& e) {
    const std::string keyword = KeywordOf(e.parameter());
    py::object error = (*input_error_type)(keyword + ": " + e.message());
    error.attr("path") = keyword;
    PyErr_SetObject(input_error_type->ptr(), error.ptr());
  } catch (const InputError& e) {
    py::object error = (*input_error_type)(e.what());
    error.attr("path") = e.json_path();
    PyErr_SetObject(input_error_type->ptr(), error.ptr());
  } catch (const drillwave::NumericalError& e) {
    py::object error = (*numerical_error_type)(e.what());
    error.attr("time") = e.time();
    error.attr("state") = py::cast(e.state());
    PyErr_SetObject(numerical_error_type->ptr(), error.ptr());
  }
}

py::object Document(const py::object& case_, const py::object& overrides) {
  return FromJson(CaseDocument(case_, overrides));
}

std::vector<double> SweepValues(const py::object& values) { return Values(values); }

py::dict Kinds() {
  py::dict kinds;
  for (const auto& kind : drillwave::cases::AllKinds())
    kinds[py::str(kind->name())] =
        py::dict(py::arg("description") = kind->description(), py::arg("fields") = FromJson(kind->FieldSchema()));
  return kinds;
}

}  // namespace

PYBIND11_MODULE(drillwave, m) {
  m.doc() =
      "drillwave: drill-string vibration simulation (d'Alembert wave networks, delay equations). The calls release "
      "Python's GIL while they work, so Python threads (and Dask's threaded workers) run them side by side; "
      "drillwave_dask submits them to a Dask cluster.";
  m.attr("__version__") = DRILLWAVE_VERSION;

  // Created once and never destroyed: the translator may run until the interpreter exits.
  input_error_type = new py::object(py::exception<InputError>(m, "InputError", PyExc_ValueError));
  numerical_error_type =
      new py::object(py::exception<drillwave::NumericalError>(m, "NumericalError", PyExc_RuntimeError));
  py::register_exception_translator(&TranslateErrors);

  m.def("run", &Run, py::arg("case") = py::none(), py::arg("set") = py::none(), py::arg("max_samples") = py::none(),
        R"(Runs a case: a file name, a dict, or None for the embedded default case.

set: overrides, {"/json/pointer": value} or ["/json/pointer=value", ...] (the command line's --set).
max_samples: refuse cases asking for more output samples or integration steps (default 1e7).
Returns {"name", "kind", "channels": {"time_s": array, <channel>: array, ...}, "summary": dict,
"expectations": [{"key", "passed", "detail"}], "case": the document as run}.
Raises drillwave.InputError (a ValueError naming the JSON path) for bad input, drillwave.NumericalError
(a RuntimeError with .time and .state) if the integration fails.)");
  m.def("sweep", &Sweep, py::arg("case"), py::arg("param"), py::arg("values"), py::arg("set") = py::none(),
        py::arg("jobs") = py::none(), py::arg("max_samples") = py::none(),
        R"(Runs a case once for each value of the parameter at the JSON pointer `param` (in parallel on `jobs`
threads, default: every CPU this process may run on). values: "first:last:count", "v1,v2,..." or a sequence of numbers.
Returns {"param", "points": [{"value", "ok", "summary", "error"}], "wall_time_s"}; a run that fails
numerically has ok False and its message in "error". Raises drillwave.InputError before anything runs when the
work (runs x the first run's samples, each at least 1e4) is above 100 x max_samples (1e9 by default).)");
  m.def("stability", &Stability, py::arg("case") = py::none(), py::arg("param") = py::none(),
        py::arg("values") = py::none(), py::arg("set") = py::none(), py::arg("jobs") = py::none(),
        py::arg("max_samples") = py::none(),
        R"(Steady states at the inputs' final values and the characteristic roots of the linearization about each:
{"name", "kind", "operating_points": [{"steady_state", "stable", "spectral_abscissa", "essential_abscissa",
"roots": [[re, im, residual], ...]}]}. With param and values, a stability map over that parameter:
{"param", "rows": [{"value", "branch", "speed_rad_s", "spectral_abscissa", "frequency_rad_s",
"essential_abscissa", "stable"}]}.)");
  m.def("diagnose", &Diagnose, py::arg("case"), py::arg("recording"), py::arg("sidecar") = py::none(),
        py::arg("set") = py::none(), py::arg("maps") = py::none(), py::arg("fit_window") = py::none(),
        py::arg("held_out") = py::none(), py::arg("margin") = 0.2, py::arg("jobs") = py::none(),
        py::arg("max_samples") = py::none(),
        R"(The diagnosis loop, as `drillwave diagnose`: effects proposed by evidence, fitted on the fit window and
kept when the held-out error falls by the margin. recording: a CSV file with time_s. sidecar: a synthetic
recording's operator sidecar (file or dict). maps: ["recording_channel=model_channel[*scale]", ...]; fit_window,
held_out: (begin, end) in recording time [s] (default: the usable recording's halves). Returns diagnosis.json's
content ("hypotheses", "held_out", "fit", "candidates", "fitted_parameters", ...) and "fitted_case".)");
  m.def("estimate", &Estimate, py::arg("case"), py::arg("recording"), py::arg("from_channels"),
        py::arg("sidecar") = py::none(), py::arg("set") = py::none(), py::arg("window") = py::none(),
        py::arg("fuse") = "", py::arg("fuse_delay") = py::none(), py::arg("fuse_time_constant") = 20.0,
        R"(A virtual downhole sensor, as `drillwave estimate`: the bit's speed, torque, weight on bit and stuck flag
estimated from the surface channels named in from_channels (e.g. "top_rpm,top_torque_kNm,hookload_kN"; the downhole
channels are never read for the estimate), with a case (typically diagnose's "fitted_case"; a sidecar moves it to a
synthetic recording's operating point). window: (begin, end) [s] of the error figures (default: all). Returns
estimate.json's content ("method", "latency_s", "stuck_events", "severity_windows", "errors" against the downhole
channels the recording holds, ...) and "channels": NumPy arrays time_s, bit_rpm, bit_rpm_band, bit_torque_Nm,
bit_torque_Nm_band, wob_N, wob_N_band, bit_stuck (bands: two standard deviations; NaN where not estimated).
fuse: downhole telemetry channels fused at their delay (e.g. "bit_rpm,wob_kN", as --fuse), the delay fuse_delay [s]
or read from the bit speed channel, the innovation low-passed over fuse_time_constant [s].)");
  m.def("calibrate", &Calibrate, py::arg("case"), py::arg("recording"), py::arg("params"),
        py::arg("sidecar") = py::none(), py::arg("set") = py::none(), py::arg("maps") = py::none(),
        py::arg("fit_window") = py::none(), py::arg("held_out") = py::none(), py::arg("walkers") = 16,
        py::arg("steps") = 60, py::arg("burn_in") = 20, py::arg("predictive_draws") = 40, py::arg("seed") = 1,
        py::arg("jobs") = py::none(), py::arg("max_samples") = py::none(),
        R"(The posterior of a case's parameters given a recording, as `drillwave calibrate`: params
["/pointer:lower:upper", ...] (uniform priors), the diagnosis loop's feature likelihood, an affine-invariant ensemble
sampler. Returns posterior.json's content ("parameters" with each one's median and 90 % interval, "predictive" with
the held-out features' bands, "coverage_90", "acceptance", ...), "samples" ([step, walker, log_likelihood, values...]
after burn-in) and "map_case" (the sample of highest likelihood).)");
  m.def("case_document", &Document, py::arg("case") = py::none(), py::arg("set") = py::none(),
        R"(The case document as the other calls read it (a file, a dict or None for the embedded default case, with the
overrides `set` applied), as a dict; nothing is checked beyond the JSON and the pointers. drillwave_dask sends it
to its workers instead of a file name.)");
  m.def("sweep_values", &SweepValues, py::arg("values"),
        R"(The values a sweep takes for "first:last:count", "v1,v2,..." or a sequence of numbers, as a list of floats.)");
  m.def("kinds", &Kinds, "The model kinds: {kind: {\"description\", \"fields\": {field: description}}}.");
}
