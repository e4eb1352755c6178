#include "drilling_run.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"

namespace drillwave::cases {

double RunawaySpeed(const model::Schedule& top_speed) {
  double fastest = 1;
  for (const auto& knot : top_speed.knots()) fastest = std::max(fastest, std::abs(knot.second));
  return kRunawaySpeedFactor * fastest;
}

void ThrowIfRunaway(double t, double bit_speed, double runaway, const std::vector<double>& state) {
  if (std::abs(bit_speed) <= runaway) return;
  throw NumericalError("runaway: the bit turns at " + Significant(bit_speed, 4) + " rad/s, over " +
                           Significant(kRunawaySpeedFactor, 3) + " times the fastest commanded speed (" +
                           Significant(runaway, 4) +
                           " rad/s): the model grows without bound here (an unstable "
                           "law, gain or delay)",
                       t, state);
}

void SummarizeDrillingRun(DrillingSamples& s, std::vector<double> hookload, const std::vector<StuckInterval>& stuck,
                          const RunSettings& settings, const SteadyDrillingValues& steady,
                          const integration::IntegrationStats& stats, RunResult& result) {
  result.summary =
      ComputeStickSlipStatistics(stuck, s.time, s.bit, s.angle, settings.window_begin_s, settings.window_end_s)
          .ToJson();
  double wob_sum = 0, rop_sum = 0, off_sum = 0, torque_sum = 0;
  int n = 0;
  for (std::size_t i = 0; i < s.time.size(); ++i)
    if (s.time[i] >= settings.window_begin_s && s.time[i] <= settings.window_end_s)
      wob_sum += s.wob[i], rop_sum += s.vbit[i], off_sum += s.off[i], torque_sum += s.bit_torque[i], ++n;
  nlohmann::json& summary = result.summary;
  summary["wob_mean_N"] = n ? wob_sum / n : 0.0;
  summary["bit_torque_mean_Nm"] = n ? torque_sum / n : 0.0;
  summary["rop_mean_m_h"] = n ? 3600 * rop_sum / n : 0.0;
  summary["off_bottom_fraction"] = n ? off_sum / n : 0.0;
  summary["steady_depth_of_cut_m"] = steady.depth;
  summary["steady_rop_m_h"] = 3600 * steady.rop;
  summary["steady_bit_torque_Nm"] = steady.tob;
  summary["steps"] = stats.steps;
  summary["events"] = stats.events;
  summary["derivative_evaluations"] = stats.derivative_evaluations;
  summary["history_rejections"] = stats.history_rejections;
  result.channels = {{"top_rpm", ToRpm(s.top)},
                     {"bit_rpm", ToRpm(s.bit)},
                     {"top_torque_Nm", std::move(s.top_torque)},
                     {"bit_torque_Nm", std::move(s.bit_torque)},
                     {"bit_angle_rad", std::move(s.angle)},
                     {"bit_stuck", std::move(s.stuck)},
                     {"wob_N", std::move(s.wob)}};
  if (!hookload.empty()) result.channels.push_back({"hookload_N", std::move(hookload)});
  result.channels.push_back({"depth_of_cut_m", std::move(s.depth)});
  result.channels.push_back({"bit_axial_speed_m_s", std::move(s.vbit)});
  result.channels.push_back({"cut_delay_s", std::move(s.tn)});
  result.channels.push_back({"off_bottom", std::move(s.off)});
  result.plot_panels = {{"top_rpm", "bit_rpm"}, {"top_torque_Nm", "bit_torque_Nm"}, {"wob_N"}, {"depth_of_cut_m"}};
  result.time_s = std::move(s.time);
}

}  // namespace drillwave::cases
