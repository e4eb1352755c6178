// A consumer of the drillwave package: runs the embedded default case (or the case file given), shortened, through
// the library and checks that it sticks and slips and that its steady sliding is linearly stable.
#include <cstdlib>
#include <iostream>
#include <string>

#include <drillwave/cases/case_runner.hpp>
#include <drillwave/cases/stability.hpp>
#include <drillwave/core/error.hpp>
#include <drillwave/io/json_reader.hpp>

#ifdef DRILLWAVE_SOURCE_DIR
#error "drillwave's source directory leaks into its consumers"
#endif

int main(int argc, char** argv) {
  try {
    nlohmann::json doc = argc > 1 ? drillwave::io::LoadJsonFile(argv[1])
                                  : nlohmann::json::parse(drillwave::cases::DefaultCaseText());
    doc["simulation"]["duration_s"] = 20;
    doc["statistics"]["window_s"] = {10, 20};
    doc.erase("expect");
    const drillwave::cases::Case c = drillwave::cases::ParseCase(doc);
    const drillwave::cases::CaseRun run = drillwave::cases::RunCase(c);
    const double stick_fraction = run.summary.at("stick_fraction").get<double>();
    const double max_speed = run.summary.at("bit_speed_max_rad_s").get<double>();
    const auto stability = drillwave::cases::AnalyzeStability(c);
    std::cout << "consumer: " << c.name << " (kind " << c.kind << "): stick fraction " << stick_fraction
              << ", bit speed max " << max_speed << " rad/s, " << stability.size() << " steady state(s)";
    if (!stability.empty()) std::cout << ", rightmost root " << stability[0].spectrum.spectral_abscissa << " 1/s";
    std::cout << std::endl;
    // The default string sticks and slips at 10 rad/s, overshooting the top speed, while its steady sliding is stable.
    if (!(stick_fraction > 0.2 && max_speed > 15 && stability.size() == 1 && stability[0].spectrum.stable)) {
      std::cerr << "consumer: unexpected result" << std::endl;
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "consumer: " << e.what() << std::endl;
    return 2;
  }
}
