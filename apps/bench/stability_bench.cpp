// `drillwave_bench stability`: the cost of two-parameter stability maps (linear analysis only): the saldivar string
// (one section: scalar neutral form) and the collars string (two sections: wave network with the robust essential
// abscissa, shared by neighbours with the same difference operator) on 100 x 100 grids, on 1 and 2 threads; the coupled
// axial-torsional string (27 states) by the full spectrum and by continued roots; and `run`'s linear-verdict note
// against the run itself on a Kelvin-Voigt string in many sub-sections.
#include <cstdio>
#include <ctime>
#include <string>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/cases/stability.hpp"
#include "drillwave/cases/stability_map.hpp"
#include "drillwave/io/json_reader.hpp"

namespace {

double CpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

// `run`'s note (cases::AddLinearVerdict: the count right of the axis, then the abscissa bisected on it) against the
// run and against the full spectra the note was computed from before (cases::AnalyzeStability), CPU seconds.
void BenchVerdictNote() {
  std::printf("## the linear-verdict note of `run` (saldivar-kelvin-voigt, CPU seconds)\n\n");
  std::printf("| sub-sections | run | note | note's share | full spectra (the former note) | note |\n"
              "|---|---|---|---|---|---|\n");
  nlohmann::json doc =
      drillwave::io::LoadJsonFile(std::string(DRILLWAVE_SOURCE_DIR) + "/json-cases/saldivar-kelvin-voigt.json");
  for (int parts : {10, 20}) {
    doc["model"]["string"]["damping_subsections"] = parts;
    const drillwave::cases::Case c = drillwave::cases::ParseCase(doc);
    double start = CpuSeconds();
    drillwave::cases::CaseRun run = drillwave::cases::RunCase(c);
    const double run_s = CpuSeconds() - start;
    start = CpuSeconds();
    drillwave::cases::AddLinearVerdict(c, run.summary);
    const double note_s = CpuSeconds() - start;
    start = CpuSeconds();
    drillwave::cases::AnalyzeStability(c, {}, drillwave::cases::ContinuumRoots::kSkipped);
    const double full_s = CpuSeconds() - start;
    std::printf("| %d | %.3f | %.3f | %.0f %% | %.3f | %s |\n", parts, run_s, note_s, 100 * note_s / (run_s + note_s),
                full_s, run.summary.value("linear_verdict", std::string("(none)")).c_str());
    std::fflush(stdout);
  }
  std::printf("\nGoal (issue 33): the note no more than 20 %% of `run`.\n\n");
}

}  // namespace

int BenchStabilityMap() {
  using drillwave::cases::ParseMapAxis;
  BenchVerdictNote();
  std::printf("## two-parameter stability maps (linear analysis, top speed x bit inertia)\n\n");
  std::printf("| case | grid | threads | wall [s] | ms per point |\n|---|---|---|---|---|\n");
  for (const auto& [name, n] : {std::pair<std::string, int>{"saldivar-stickslip", 100}, {"saldivar-collars", 100}}) {
    const nlohmann::json doc =
        drillwave::io::LoadJsonFile(std::string(DRILLWAVE_SOURCE_DIR) + "/json-cases/" + name + ".json");
    const std::string count = std::to_string(n);
    for (int jobs : {1, 2}) {
      const drillwave::cases::StabilityMapSpec spec{ParseMapAxis("/model/top/speed_rad_s/knots/1/1=4:16:" + count, doc),
                                                    ParseMapAxis("/model/bit/inertia_kgm2=50:150:" + count, doc), jobs,
                                                    false};
      const auto result = drillwave::cases::StabilityMap2D(doc, spec);
      std::printf("| %s | %d x %d | %d | %.2f | %.3f |\n", name.c_str(), n, n, jobs, result.linear_wall_time_s,
                  1e3 * result.linear_wall_time_s / (n * n));
      std::fflush(stdout);
    }
  }
  std::printf("\nGoal: 100 x 100 linear points under 10 s on 2 cores.\n\n");

  // The coupled model (5 sub-sections, 27 states): rpm x WOB, the full spectrum at every point (the reference) on a
  // small grid, the continued and certified rightmost roots on the same grid and on 100 x 100.
  std::printf("## coupled axial-torsional map (baseline-coupled-stability, rpm x WOB, 2 threads)\n\n");
  std::printf("| method | grid | wall [s] | CPU [s] | ms CPU per point | full spectra | verdicts differing from full |\n"
              "|---|---|---|---|---|---|---|\n");
  const nlohmann::json coupled =
      drillwave::io::LoadJsonFile(std::string(DRILLWAVE_SOURCE_DIR) + "/json-cases/baseline-coupled-stability.json");
  double cpu_s = 0;  // of the last map (std::clock: the process's CPU time over both threads)
  auto coupled_map = [&](int n, bool full) {
    const std::string count = std::to_string(n);
    const drillwave::cases::StabilityMapSpec spec{ParseMapAxis("/model/top/speed_rad_s=4.18879:16.75516:" + count, coupled),
                                                  ParseMapAxis("/model/hoist/weight_on_bit_N=50000:160000:" + count,
                                                               coupled),
                                                  2, false, full};
    const std::clock_t start = std::clock();
    auto result = drillwave::cases::StabilityMap2D(coupled, spec);
    cpu_s = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
    return result;
  };
  const int small = 6;
  const auto reference = coupled_map(small, true);
  const double full_ms = 1e3 * cpu_s / (small * small);
  std::printf("| full spectrum | %d x %d | %.2f | %.2f | %.2f | %d | - |\n", small, small, reference.linear_wall_time_s,
              cpu_s, full_ms, reference.full_spectra);
  const auto continued = coupled_map(small, false);
  int differing = 0;
  for (std::size_t k = 0; k < reference.cells.size(); ++k)
    differing += reference.cells[k].verdict != continued.cells[k].verdict;
  std::printf("| continued | %d x %d | %.2f | %.2f | %.2f | %d | %d |\n", small, small, continued.linear_wall_time_s,
              cpu_s, 1e3 * cpu_s / (small * small), continued.full_spectra, differing);
  std::fflush(stdout);
  const auto large = coupled_map(100, false);
  const double large_ms = 1e3 * cpu_s / 1e4;
  std::printf("| continued | 100 x 100 | %.2f | %.2f | %.3f | %d | (not computed) |\n", large.linear_wall_time_s, cpu_s,
              large_ms, large.full_spectra);
  std::printf("\nFull spectrum over continued, CPU per point: %.0f x. Goal: the coupled 100 x 100 map under 10 s on 2 "
              "cores.\n", full_ms / large_ms);
  return 0;
}
