#include "drillwave/integration/options.hpp"

#include "drillwave/core/validity.hpp"

namespace drillwave::integration {

bool IntegratorOptions::IsValid(std::string* error) const {
  auto positive_or_unlimited = [&](const char* parameter, double value) {
    return value > 0 ||
           Invalid(error, parameter, "expected a number > 0 (inf: no limit), got " + ReadableNumber(value));
  };
  return PositiveField(error, "abs_tol", abs_tol) && PositiveField(error, "rel_tol", rel_tol) &&
         PositiveField(error, "initial_step", initial_step) && positive_or_unlimited("max_step", max_step) &&
         PositiveField(error, "event_time_tol", event_time_tol) &&
         WholeField(error, "max_events_at_one_instant", max_events_at_one_instant, 1) &&
         NonNegativeField(error, "history_step_floor", history_step_floor) &&
         WholeField(error, "max_steps", max_steps, 0) && WholeField(error, "max_evaluations", max_evaluations, 0) &&
         positive_or_unlimited("max_planned_steps", max_planned_steps);
}

}  // namespace drillwave::integration
