// Benchmark (no assertions): wall time per simulated second of the saldivar stick–slip case on the wave engine at
// several tolerances, and of the independent lumped reference (tests/support/lumped_string.hpp) at increasing N,
// with each run's stick–slip period error against a tight engine run, all measured in this one run.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/io/json_reader.hpp"
#include "lumped_string.hpp"

namespace {

using drillwave::cases::Case;

struct Timing {
  double wall_s;  // best of the repeats, integration and statistics (no output files)
  nlohmann::json summary;
};

Timing RunEngine(nlohmann::json doc, double tol, double output_interval, int repeats) {
  doc["simulation"]["abs_tol"] = tol;
  doc["simulation"]["rel_tol"] = tol;
  doc["simulation"]["output_interval_s"] = output_interval;
  const Case c = drillwave::cases::ParseCase(doc);
  Timing best{INFINITY, {}};
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    const auto run = drillwave::cases::RunCase(c);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (wall < best.wall_s) best = {wall, run.summary};
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string file = argc > 1 ? argv[1] : std::string(DRILLWAVE_SOURCE_DIR) + "/json-cases/saldivar-stickslip.json";
  const nlohmann::json doc = drillwave::io::LoadJsonFile(file);
  const double duration = doc["simulation"]["duration_s"].get<double>();
  const double reference_period = RunEngine(doc, 1e-11, 0.1, 1).summary["stick_slip_period_s"].get<double>();
  std::printf("# drillwave bench: %s, %.0f s simulated; period reference (engine, tol 1e-11) = %.9f s\n\n",
              file.c_str(), duration, reference_period);

  std::printf("| method | setting | period error (rel.) | wall time [ms] | ms per simulated s | faster than real time |\n");
  std::printf("|---|---|---|---|---|---|\n");
  double engine_error = 0, engine_wall = 0;
  for (double tol : {1e-3, 1e-4, 1e-6, 1e-8}) {
    for (double interval : {0.1, 0.005}) {
      const Timing t = RunEngine(doc, tol, interval, 20);
      const double err = std::abs(t.summary["stick_slip_period_s"].get<double>() - reference_period) / reference_period;
      std::printf("| wave engine | tol %.0e, output every %g s | %.2e | %.3f | %.4f | %.0fx |\n", tol, interval, err,
                  1e3 * t.wall_s, 1e3 * t.wall_s / duration, duration / t.wall_s);
      if (tol == 1e-4 && interval == 0.1) engine_error = err, engine_wall = t.wall_s;
    }
  }

  drillwave::reference::LumpedStringParams params;
  drillwave::integration::IntegratorOptions o;
  o.abs_tol = o.rel_tol = 1e-6;
  double best_reference_error = INFINITY, best_reference_wall = 0;
  for (int n : {10, 20, 40, 80, 160}) {
    const auto start = std::chrono::steady_clock::now();
    const auto r = drillwave::reference::SimulateLumpedString(params, n, duration, 40, o);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double err = std::abs(r.stick_slip_period_s - reference_period) / reference_period;
    std::printf("| lumped reference | N = %d, tol 1e-6 | %.2e | %.1f | %.3f | %.0fx |\n", n, err, 1e3 * wall,
                1e3 * wall / duration, duration / wall);
    best_reference_error = err, best_reference_wall = wall;
  }
  std::printf("\nThe engine at tol 1e-4 (period error %.1e) takes %.2f ms; the reference's most accurate run (N = 160,\n"
              "period error %.1e, still %.0fx less accurate) takes %.0f ms: at equal accuracy the engine is at least %.0fx faster.\n",
              engine_error, 1e3 * engine_wall, best_reference_error, best_reference_error / std::max(engine_error, 1e-16),
              1e3 * best_reference_wall, best_reference_wall / engine_wall);
  return 0;
}
