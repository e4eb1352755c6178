// `drillwave_bench stability`: the cost of two-parameter stability maps (linear analysis only): the saldivar string
// (one section: scalar neutral form) on a 100 x 100 grid and the collars string (two sections: wave network with the
// robust essential abscissa) on a coarser one, on 1 and 2 threads.
#include <cstdio>
#include <string>

#include "drillwave/cases/stability_map.hpp"
#include "drillwave/io/json_reader.hpp"

int BenchStabilityMap() {
  using drillwave::cases::ParseMapAxis;
  std::printf("## two-parameter stability maps (linear analysis, top speed x bit inertia)\n\n");
  std::printf("| case | grid | threads | wall [s] | ms per point |\n|---|---|---|---|---|\n");
  for (const auto& [name, n] : {std::pair<std::string, int>{"saldivar-stickslip", 100}, {"saldivar-collars", 20}}) {
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
  std::printf("\nGoal: 100 x 100 linear points of the one-section string under 10 s on 2 cores.\n");
  return 0;
}
