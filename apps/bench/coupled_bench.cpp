// `drillwave_bench coupled`: the coupled axial–torsional kind's cost per simulated second (issue 11's goals: the
// baseline at 60 rpm under 2 ms, the bouncing bit at 3000 m / 150 kN under 20 ms per simulated second) over a ladder
// of tolerances, with the statistics each tolerance gives beside the tightest run's, measured in this one run.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/io/json_reader.hpp"

namespace {

struct CoupledRun {
  double wall_s = INFINITY;  // best of the repeats
  nlohmann::json summary;
};

CoupledRun RunCoupled(nlohmann::json doc, double tol, int repeats) {
  doc["simulation"]["abs_tol"] = tol;
  doc["simulation"]["rel_tol"] = tol;
  doc["simulation"]["output_interval_s"] = 0.01;
  const drillwave::cases::Case c = drillwave::cases::ParseCase(doc);
  CoupledRun best;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    drillwave::cases::CaseRun run = drillwave::cases::RunCase(c);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (wall < best.wall_s) best = {wall, std::move(run.summary)};
  }
  return best;
}

double Number(const nlohmann::json& s, const char* key) {
  return s.contains(key) && s.at(key).is_number() ? s.at(key).get<double>() : NAN;
}

void BenchCase(const std::string& title, const nlohmann::json& doc) {
  const double duration = doc["simulation"]["duration_s"].get<double>();
  std::printf("### %s (%g s simulated)\n\n", title.c_str(), duration);
  std::printf("| tol | ms per simulated s | steps | evaluations | history rejections | oscillation period [s] | "
              "stick fraction | off bottom | mean WOB [kN] |\n|---|---|---|---|---|---|---|---|---|\n");
  for (double tol : {1e-4, 1e-5, 1e-6, 1e-7}) {
    const CoupledRun r = RunCoupled(doc, tol, tol >= 1e-5 ? 3 : 1);
    const auto& s = r.summary;
    std::printf("| %.0e | %.2f | %.0f | %.0f | %.0f | %.5f | %.4f | %.4f | %.2f |\n", tol, 1e3 * r.wall_s / duration,
                Number(s, "steps"), Number(s, "derivative_evaluations"), Number(s, "history_rejections"),
                Number(s, "oscillation_period_s"), Number(s, "stick_fraction"), Number(s, "off_bottom_fraction"),
                1e-3 * Number(s, "wob_mean_N"));
    std::fflush(stdout);
  }
  std::printf("\n");
}

}  // namespace

int BenchCoupled() {
  const nlohmann::json baseline =
      drillwave::io::LoadJsonFile(std::string(DRILLWAVE_SOURCE_DIR) + "/json-cases/baseline-60rpm.json");
  std::printf("## coupled axial–torsional kind (cases::RunCase, best of 3 down to tol 1e-5, output every 10 ms)\n\n");
  BenchCase("baseline-60rpm: stick-slip", baseline);
  // The formation diagnose and the README's commands use (BASELINE.md's 1 % rock strength heterogeneity, 2 mm
  // correlation): the bit's strength summed over its 64 modes at every evaluation, against homogeneous rock above.
  nlohmann::json heterogeneous = baseline;
  heterogeneous["model"]["rock"]["strength_heterogeneity"] = {{"std", 0.01}, {"correlation_m", 0.002}, {"seed", 1}};
  BenchCase("baseline-60rpm on 1 % heterogeneous rock", heterogeneous);
  nlohmann::json bouncing = baseline;  // the bouncing bit of tests/cases/axial_torsional_test.cpp
  bouncing["model"]["string"]["length_m"] = 3000;
  bouncing["model"]["hoist"]["weight_on_bit_N"] = 150000;
  bouncing["simulation"]["duration_s"] = 50;
  bouncing["statistics"]["window_s"] = {30, 50};
  bouncing.erase("expect");
  BenchCase("bouncing bit: 3000 m, 150 kN, 60 rpm", bouncing);
  return 0;
}
