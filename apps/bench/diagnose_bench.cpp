// drillwave_bench diagnose [recNN ...]: the diagnosis loop's cost on synthetic recordings of ../shared (issue 13's
// goal: one recording with all candidates under 60 s on 2 cores; issue 32's: under 90 s). Per recording: wall time
// of the loop with 2 threads and of its costliest stages, model runs, and the wall time of one baseline run measured
// in the same process, as the reference unit.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/stopwatch.hpp"
#include "drillwave/diagnosis/comparison.hpp"
#include "drillwave/diagnosis/loop.hpp"
#include "drillwave/diagnosis/recording.hpp"
#include "drillwave/diagnosis/sidecar.hpp"
#include "drillwave/io/json_reader.hpp"

int BenchDiagnose(const std::vector<std::string>& names) {
  namespace dg = drillwave::diagnosis;
  const std::filesystem::path dir = std::filesystem::path(DRILLWAVE_SOURCE_DIR) / ".." / "shared" / "recordings" /
                                    "synthetic";
  if (!std::filesystem::exists(dir / "rec01.csv")) {
    std::printf("no synthetic recordings at %s\n", dir.string().c_str());
    return 1;
  }
  nlohmann::json baseline =
      drillwave::io::LoadJsonFile(std::string(DRILLWAVE_SOURCE_DIR) + "/json-cases/baseline-60rpm.json");
  // The formation every recording of the family drills, as scripts/score_recordings.py and docs/diagnosis.md's
  // command give it to the base case.
  baseline["model"]["rock"]["strength_heterogeneity"] = {{"std", 0.01}, {"correlation_m", 0.002}, {"seed", 1}};
  std::printf(
      "# diagnosis loop (2 threads)\n\n| recording | loop wall [s] | model runs | one baseline run [s] | "
      "loop / baseline run | calibration [s] | selection [s] | the model that stands [s] | kept |\n"
      "|---|---|---|---|---|---|---|---|---|\n");
  for (const std::string& name : names) {
    const nlohmann::json doc = dg::CaseFromSidecar(drillwave::io::LoadJsonFile((dir / (name + ".json")).string()),
                                                   baseline, dg::kSidecarWarmupS, name + ".json");
    const dg::Recording rec = dg::LoadRecording((dir / (name + ".csv")).string());
    // The options `drillwave diagnose CASE REC --sidecar S -j 2` uses: its windows, sampling and channel maps.
    const drillwave::cases::Case c = drillwave::cases::ParseCase(doc);
    dg::LoopOptions o = dg::DefaultLoopOptions(c, rec, dg::kSidecarWarmupS);
    o.maps = dg::ResolveChannelMaps({}, rec, dg::ProbeChannels(c));
    o.threads = 2;
    const drillwave::Stopwatch run_clock;
    drillwave::cases::RunCase(c);
    const double one_run = run_clock.Seconds();
    const drillwave::Stopwatch loop_clock;
    const dg::DiagnosisLoop loop = dg::RunDiagnosisLoop(doc, rec, o);
    const double wall = loop_clock.Seconds();
    std::string kept;
    if (loop.kept >= 0)
      for (const std::string& e : loop.candidates[loop.kept].effects) kept += e + " ";
    const dg::LoopTimes& stage = loop.wall_seconds;
    std::printf("| %s | %.1f | %d | %.2f | %.1f | %.1f | %.1f | %.1f | %s|\n", name.c_str(), wall, loop.model_runs,
                one_run, wall / one_run, stage.calibration, stage.selection, stage.fitted, kept.c_str());
    std::fflush(stdout);
  }
  return 0;
}
