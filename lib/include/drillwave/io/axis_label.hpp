#pragma once
// Axis labels that name a quantity and its unit ("bit speed [rpm]", "bit inertia [kg m²]") from the names drillwave
// already gives its channels and case fields, which end in their unit: "bit_rpm", "top_torque_Nm", "inertia_kgm2".
#include <string>
#include <vector>

namespace drillwave::io {

struct Quantity {
  std::string name;  // in words, e.g. "top torque"; symbols such as "T_s" or "mu_s" are kept as written
  std::string unit;  // e.g. "N m"; empty when the name ends in no known unit (a ratio, a flag, a count)
};

// A channel or field name with its unit as the last "_"-separated part(s): "top_torque_Nm" -> {"top torque", "N m"},
// "bit_rpm" -> {"bit speed", "rpm"}, "tob_Nm" -> {"torque on bit", "N m"}, "mu_s" -> {"mu_s", ""} (a subscript).
Quantity QuantityOfName(const std::string& name);

// A case parameter's JSON pointer: its field, named by the objects above it, "/model/bit/inertia_kgm2" ->
// {"bit inertia", "kg m²"}; a schedule's knot, "/model/top/speed_rad_s/knots/1/1" -> {"top speed at knot 1",
// "rad/s"}, and its time, ".../knots/1/0" -> {"top speed: time of knot 1", "s"}.
Quantity QuantityOfPointer(const std::string& pointer);

// "name [unit]", or the name alone when there is no unit.
std::string AxisLabel(const Quantity& quantity);

// One axis for channels plotted together: "top speed, bit speed [rpm]" when they share a unit, else each with its
// own: "bit speed [rpm], bit torque [N m]".
std::string AxisLabelOfChannels(const std::vector<std::string>& channel_names);

}  // namespace drillwave::io
