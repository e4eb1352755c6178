// drillwave bench (no assertions): how fast the wave engine runs the saldivar stick–slip case, and how it compares
// with the independent lumped N-element reference (tests/support/lumped_reference.hpp) at equal accuracy of the
// stick–slip period. Everything is measured in this one run, on this machine.
//
//   drillwave_bench [case.json] [engine tolerance for the equal-accuracy comparison, default 1e-3]
//                   [time budget for one reference run in s, default 30]
//   drillwave_bench delay      (only the generic delay solver against RADAR5's figures)
//   drillwave_bench diagnose [recNN ...]   (the diagnosis loop on synthetic recordings; default rec01 rec07)
//   drillwave_bench coupled    (the coupled axial–torsional kind per simulated second, over tolerances)
//   drillwave_bench stability  (100 x 100 stability maps, torsional and coupled)
//
// Errors are relative to a tight engine run (tol 1e-11). Wall times are the best of several repeats of
// cases::RunCase (integration and statistics, no output files) or of the reference's integration.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <functional>
#include <string>
#include <vector>

#include "delay_problems.hpp"
#include "drillwave/cases/case_runner.hpp"
#include "drillwave/io/json_reader.hpp"
#include "lumped_reference.hpp"

namespace {

namespace lr = drillwave::lumped_reference;

struct EngineRun {
  double tol, output_interval_s;
  double wall_s;  // best of the repeats
  double period_s, stick_fraction, speed_mean;
  long steps, evaluations;
};

EngineRun RunEngine(nlohmann::json doc, double tol, double output_interval_s, int repeats) {
  doc["simulation"]["abs_tol"] = tol;
  doc["simulation"]["rel_tol"] = tol;
  doc["simulation"]["output_interval_s"] = output_interval_s;
  const drillwave::cases::Case c = drillwave::cases::ParseCase(doc);
  EngineRun best{tol, output_interval_s, INFINITY, NAN, NAN, NAN, 0, 0};
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    const drillwave::cases::CaseRun run = drillwave::cases::RunCase(c);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (wall >= best.wall_s) continue;
    const auto& s = run.summary;
    best.wall_s = wall;
    best.period_s = s["stick_slip_period_s"].is_number() ? s["stick_slip_period_s"].get<double>() : NAN;
    best.stick_fraction = s["stick_fraction"].get<double>();
    best.speed_mean = s["bit_speed_mean_rad_s"].get<double>();
    best.steps = s["steps"].get<long>();
    best.evaluations = s["derivative_evaluations"].get<long>();
  }
  return best;
}

struct ReferenceRun {
  int n;
  double wall_s;
  lr::LumpedStringResult result;
};

ReferenceRun RunReference(const lr::LumpedStringParams& p, int n, double duration, lr::StatisticsWindow window,
                          double tol) {
  drillwave::integration::IntegratorOptions o;
  o.abs_tol = o.rel_tol = tol;
  ReferenceRun best{n, INFINITY, {}};
  for (int r = 0; r < 3; ++r) {
    const auto start = std::chrono::steady_clock::now();
    const lr::LumpedStringResult result = lr::SimulateLumpedString(p, n, duration, window, o);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (wall < best.wall_s) best = {n, wall, result};
    if (wall > 1.0) break;  // long runs vary little; one is enough
  }
  return best;
}

double RelativeError(double value, double reference) { return std::abs(value - reference) / std::abs(reference); }

// --- The generic delay solver on problems with exact solutions, next to RADAR5 v2.1 (Radau IIA, order 5) on the
// same problems: maximum dense-output error against right-hand-side evaluations over a ladder of tolerances.
struct DelayBenchProblem {
  const char* name;
  drillwave::integration::DelayProblem problem;
  double t_end;
  std::function<double(double)> exact;
  double radar5_error;  // RADAR5's dense error at tol 1e-8
  long radar5_evaluations;  // 0: not reported (RADAR5 stalls at its error)
};

void BenchDelaySolver() {
  namespace dp = drillwave::delay_problems;
  const std::vector<DelayBenchProblem> problems = {
      {"Hayashi, a = 0.9 (neutral, state-dependent, vanishing delay)", dp::HayashiProblem(0.9), dp::kPi,
       [](double t) { return std::sin(t); }, 9.4e-8, 656},
      {"ddex4 (neutral, vanishing delay t/2)", dp::NeutralCosineProblem(), dp::kPi, [](double t) { return std::cos(t); },
       9.5e-8, 366},
      {"Paul y' = y(y(t)), argument declared", dp::PaulProblem(true), dp::kPaulEnd, dp::PaulExact, 1.5e-6, 0},
      {"Paul y' = y(y(t)), argument not declared", dp::PaulProblem(false), dp::kPaulEnd, dp::PaulExact, 1.5e-6, 0},
  };
  std::printf("## generic delay solver (SolveDelayProblem) against RADAR5\n\n");
  std::printf("Error: maximum over 4001 points of the dense output; evaluations: right-hand-side calls. RADAR5 v2.1 "
              "at tol 1e-8 reaches the error in its row with the evaluations shown (on Paul's problem its dense error "
              "stalls at 1.5e-6).\n\n");
  for (const DelayBenchProblem& b : problems) {
    std::printf("### %s\n\n| tol | max dense error | evaluations | steps | redone steps |\n|---|---|---|---|---|\n",
                b.name);
    long cheapest = -1;
    double cheapest_tol = NAN, cheapest_error = NAN, smallest_error = INFINITY;
    for (int k = 12; k <= 48; ++k) {  // tol = 10^(-k/4): 1e-3 ... 1e-12
      const double tol = std::pow(10.0, -k / 4.0);
      drillwave::integration::IntegratorOptions o;
      o.abs_tol = o.rel_tol = tol;
      const drillwave::integration::DelaySolution sol = SolveDelayProblem(b.problem, b.t_end, o);
      const double error = dp::MaxDenseError(sol, b.exact, b.problem.t0, b.t_end);
      const long evals = sol.stats.derivative_evaluations;
      smallest_error = std::min(smallest_error, error);
      if (error <= b.radar5_error && (cheapest < 0 || evals < cheapest)) {
        cheapest = evals;
        cheapest_tol = tol;
        cheapest_error = error;
      }
      if (k % 4 == 0)
        std::printf("| %.0e | %.2e | %ld | %ld | %ld |\n", tol, error, evals, sol.stats.steps, sol.stats.trial_redos);
    }
    if (b.radar5_evaluations > 0)
      std::printf("\nRADAR5: %.1e with %ld evaluations. Here: %s", b.radar5_error, b.radar5_evaluations,
                  cheapest < 0 ? "not reached" : "");
    else
      std::printf("\nRADAR5: stalls at %.1e. Here: smallest error %.1e; %s", b.radar5_error, smallest_error,
                  cheapest < 0 ? "RADAR5's error not reached" : "");
    if (cheapest >= 0)
      std::printf("%.2e with %ld evaluations (tol %.1e)%s", cheapest_error, cheapest, cheapest_tol,
                  b.radar5_evaluations > 0 ? (cheapest < b.radar5_evaluations ? ", fewer than RADAR5" : ", more than RADAR5")
                                           : "");
    std::printf(".\n\n");
  }

  // Echoes of breakpoints: one delay against three incommensurate ones.
  std::printf("### y' = -(1/n) sum y(t - tau_k), y = 1 before 0, on [0, 80], tol 1e-8\n\n"
              "| delays | flagged neutral | evaluations | breakpoints stepped onto |\n|---|---|---|---|\n");
  for (bool flag_neutral : {false, true}) {
    for (const std::vector<double>& delays : {std::vector<double>{1.0}, {1.0, std::sqrt(2.0), std::sqrt(3.0)}}) {
      drillwave::integration::IntegratorOptions o;
      o.abs_tol = o.rel_tol = 1e-8;
      const auto sol = SolveDelayProblem(dp::AveragedDelaysProblem(delays, flag_neutral), 80, o);
      std::printf("| %s | %s | %ld | %ld |\n", delays.size() == 1 ? "1" : "1, sqrt 2, sqrt 3",
                  flag_neutral ? "yes" : "no", sol.stats.derivative_evaluations, sol.stats.breakpoints);
    }
  }
  std::printf("\n");
}

}  // namespace

int BenchDiagnose(const std::vector<std::string>& names);  // diagnose_bench.cpp
int BenchStabilityMap();                                    // stability_bench.cpp
int BenchCoupled();                                         // coupled_bench.cpp

static int Bench(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "diagnose") {
    std::vector<std::string> names(argv + 2, argv + argc);
    if (names.empty()) names = {"rec01", "rec07"};
    return BenchDiagnose(names);
  }
  if (argc > 1 && std::string(argv[1]) == "stability") return BenchStabilityMap();
  if (argc > 1 && std::string(argv[1]) == "coupled") return BenchCoupled();
  if (argc > 1 && std::string(argv[1]) == "delay") {
    BenchDelaySolver();
    return 0;
  }
  const std::string file =
      argc > 1 ? argv[1] : std::string(DRILLWAVE_SOURCE_DIR) + "/json-cases/saldivar-stickslip.json";
  const double chosen_tol = argc > 2 ? std::atof(argv[2]) : 1e-3;
  const double budget_s = argc > 3 ? std::atof(argv[3]) : 30.0;
  const nlohmann::json doc = drillwave::io::LoadJsonFile(file);
  const double duration = doc["simulation"]["duration_s"].get<double>();
  const double case_interval = doc["simulation"].value("output_interval_s", 1e-3);
  const lr::StatisticsWindow window{doc["statistics"]["window_s"][0].get<double>(),
                                    doc["statistics"]["window_s"][1].get<double>()};

  const EngineRun tight = RunEngine(doc, 1e-11, 0.1, 1);
  std::printf("# drillwave bench\n\ncase %s: %g s simulated, statistics over [%g, %g] s\n", file.c_str(), duration,
              window.begin_s, window.end_s);
  std::printf("reference answer (engine, tol 1e-11): stick-slip period %.10f s, stick fraction %.8f, mean bit speed "
              "%.8f rad/s\n\n", tight.period_s, tight.stick_fraction, tight.speed_mean);

  // --- The engine at several tolerances.
  std::printf("## wave engine (cases::RunCase, best of 5)\n\n");
  std::printf("| tol | output interval [s] | period error (rel.) | stick fraction error | wall [ms] | "
              "ms per simulated s | faster than real time | steps | evaluations |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  std::vector<EngineRun> engine;
  for (double tol : {1e-2, 1e-3, 1e-4, 1e-6, 1e-8}) {
    for (double interval : {0.1, case_interval}) {
      const EngineRun e = RunEngine(doc, tol, interval, 5);
      std::printf("| %.0e | %g | %.2e | %.2e | %.2f | %.4f | %.0fx | %ld | %ld |\n", tol, interval,
                  RelativeError(e.period_s, tight.period_s), std::abs(e.stick_fraction - tight.stick_fraction),
                  1e3 * e.wall_s, 1e3 * e.wall_s / duration, duration / e.wall_s, e.steps, e.evaluations);
      if (interval == 0.1) engine.push_back(e);
      if (interval == case_interval) break;  // the case's own interval is 0.1: one row is enough
    }
  }

  // --- The engine run chosen for the equal-accuracy comparison.
  const auto chosen_it = std::min_element(engine.begin(), engine.end(), [&](const EngineRun& a, const EngineRun& b) {
    return std::abs(std::log(a.tol / chosen_tol)) < std::abs(std::log(b.tol / chosen_tol));
  });
  const EngineRun chosen = *chosen_it;
  const double target = RelativeError(chosen.period_s, tight.period_s);

  // --- The lumped reference at increasing N until it is as accurate as the chosen engine run.
  const lr::LumpedStringParams params = lr::LumpedStringParams::FromCase(doc);
  const double reference_tol = 1e-6;  // its time-stepping error in the period is ~1e-8: far below its N error
  std::printf("\n## lumped N-element reference (tol %.0e, best of up to 3)\n\n", reference_tol);
  std::printf("target: the engine's period error at tol %.0e, output every 0.1 s: %.2e (%.2f ms)\n\n", chosen.tol,
              target, 1e3 * chosen.wall_s);
  std::printf("| N | period error (rel.) | stick fraction error | mean speed error (rel.) | wall [ms] | "
              "ms per simulated s | faster than real time | steps | evaluations |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  std::vector<ReferenceRun> reference;
  bool reached = false;
  for (int n = 10;; n *= 2) {
    const ReferenceRun r = RunReference(params, n, duration, window, reference_tol);
    const double err = RelativeError(r.result.stick_slip_period_s, tight.period_s);
    std::printf("| %d | %.2e | %.2e | %.2e | %.1f | %.3f | %.0fx | %ld | %ld |\n", n, err,
                std::abs(r.result.stick_fraction - tight.stick_fraction),
                RelativeError(r.result.bit_speed_mean, tight.speed_mean), 1e3 * r.wall_s, 1e3 * r.wall_s / duration,
                duration / r.wall_s, r.result.steps, r.result.evaluations);
    std::fflush(stdout);
    reference.push_back(r);
    if (err <= target) {
      reached = true;
      break;
    }
    // Doubling N costs about 4x (twice the states, half the stable step): stop before the budget is exceeded.
    if (reference.size() >= 2) {
      const double growth = r.wall_s / reference[reference.size() - 2].wall_s;
      if (r.wall_s * std::max(growth, 2.0) > budget_s) break;
    } else if (4 * r.wall_s > budget_s) {
      break;
    }
  }

  // --- Equal accuracy.
  std::printf("\n## equal accuracy of the stick-slip period\n\n");
  const ReferenceRun& last = reference.back();
  const double last_err = RelativeError(last.result.stick_slip_period_s, tight.period_s);
  if (reached) {
    std::printf("The reference reaches the engine's period error %.2e (engine tol %.0e, %.2f ms) at N = %d "
                "(error %.2e) in %.1f ms: reference / engine time = %.0fx.\n", target, chosen.tol,
                1e3 * chosen.wall_s, last.n, last_err, 1e3 * last.wall_s, last.wall_s / chosen.wall_s);
  } else {
    std::printf("Within the budget (%.0f s per run) the reference did not reach the engine's period error %.2e "
                "(engine tol %.0e): its best is %.2e at N = %d in %.1f ms.\n", budget_s, target, chosen.tol, last_err,
                last.n, 1e3 * last.wall_s);
    // Measured lower bound: the cheapest engine run at least as accurate as the reference's best one.
    const EngineRun* cheapest = nullptr;
    for (const EngineRun& e : engine)
      if (RelativeError(e.period_s, tight.period_s) <= last_err && (!cheapest || e.wall_s < cheapest->wall_s))
        cheapest = &e;
    if (cheapest)
      std::printf("Measured: the cheapest engine run at least as accurate (tol %.0e, error %.2e, %.2f ms) is %.0fx "
                  "faster than the reference's best run.\n", cheapest->tol,
                  RelativeError(cheapest->period_s, tight.period_s), 1e3 * cheapest->wall_s,
                  last.wall_s / cheapest->wall_s);
    // Extrapolation from the last two N (labelled as such, not measured).
    if (reference.size() >= 2) {
      const ReferenceRun& prev = reference[reference.size() - 2];
      const double prev_err = RelativeError(prev.result.stick_slip_period_s, tight.period_s);
      const double order = std::log(prev_err / last_err) / std::log(static_cast<double>(last.n) / prev.n);
      const double time_exponent = std::log(last.wall_s / prev.wall_s) / std::log(static_cast<double>(last.n) / prev.n);
      if (order > 0) {
        const double n_needed = last.n * std::pow(last_err / target, 1.0 / order);
        const double t_needed = last.wall_s * std::pow(n_needed / last.n, time_exponent);
        std::printf("Extrapolated (not measured): observed order %.2f in N, time ~ N^%.2f: the reference would need "
                    "N ~ %.0f and ~%.0f s, i.e. ~%.0fx the engine's time.\n", order, time_exponent, n_needed,
                    t_needed, t_needed / chosen.wall_s);
      }
    }
  }
  std::printf("\nSpec goals: >= 50000x faster than real time; >= 100x faster than the reference at equal accuracy.\n\n");
  BenchDelaySolver();
  return 0;
}

// Usage on -h/--help; a bad argument or case (a missing file, a field that is not there) ends with its message and
// exit code 2 instead of std::terminate.
int main(int argc, char** argv) {
  if (argc > 1 && (std::string(argv[1]) == "-h" || std::string(argv[1]) == "--help")) {
    std::printf(
        "drillwave_bench [case.json] [engine tolerance, default 1e-3] [budget for one reference run in s, default 30]\n"
        "drillwave_bench delay               the generic delay solver against RADAR5's figures\n"
        "drillwave_bench diagnose [recNN..]  the diagnosis loop on synthetic recordings (default rec01 rec07)\n"
        "drillwave_bench coupled             the coupled axial-torsional kind per simulated second\n"
        "drillwave_bench stability           100 x 100 stability maps\n");
    return 0;
  }
  try {
    return Bench(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "drillwave_bench: %s\n", e.what());
    return 2;
  }
}
