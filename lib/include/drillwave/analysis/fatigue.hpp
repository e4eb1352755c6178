#pragma once
// Stress-life fatigue of a sampled stress history: rainflow counting (ASTM E1049-85, sect. 5.4.4), a Basquin S-N
// curve with an endurance limit, and Palmgren-Miner damage summation. Pure functions of the history; no model.
//
//   const auto cycles = RainflowCount(stress_Pa);        // ranges, means, counts (1 or 1/2)
//   const double damage = MinerDamage(cycles, SnCurve::MildSteel());  // failure expected at 1
#include <vector>

namespace drillwave::analysis {

struct RainflowCycle {
  double range = 0;  // peak-to-valley [unit of the history]
  double mean = 0;
  double count = 1;  // 1 for a closed cycle, 0.5 for a half cycle (a range left over at the end)
};

// The history's reversals (peaks and valleys) in order, with its first and last points; plateaus and points on a
// monotone stretch are dropped. Fewer than two distinct values give one point (or none for an empty history).
std::vector<double> Reversals(const std::vector<double>& history);

// Rainflow counting of the history's reversals by the three-point rule of ASTM E1049-85 sect. 5.4.4, the start
// counted as a half cycle when it closes the range under consideration, the ranges left at the end as half cycles.
std::vector<RainflowCycle> RainflowCount(const std::vector<double>& history);

// Basquin's stress-life curve S_a = coefficient * N^exponent (stress amplitude S_a, cycles to failure N) down to
// the endurance limit, below which N is infinite. Mean stress is not corrected for (fully reversed data).
struct SnCurve {
  double coefficient_Pa = 0;     // a > 0
  double exponent = 0;           // b < 0
  double endurance_limit_Pa = 0;  // S_e >= 0; amplitudes below it do no damage

  // Cycles to failure at the amplitude (infinity below the endurance limit).
  double CyclesToFailure(double amplitude_Pa) const;

  // Mild steel of ultimate strength 400 MPa by the usual estimates for wrought steel (Shigley's Mechanical
  // Engineering Design, sect. 6-7): S_e = 0.5 S_ut at 1e6 cycles, S = 0.9 S_ut at 1e3 cycles, Basquin between:
  // a = (0.9 S_ut)^2 / S_e = 648 MPa, b = -log10(0.9 S_ut / S_e) / 3 = -0.0851.
  static SnCurve MildSteel();
};

// Palmgren-Miner: sum over the cycles of count / N_f(range / 2).
double MinerDamage(const std::vector<RainflowCycle>& cycles, const SnCurve& curve);

}  // namespace drillwave::analysis
