// io/axis_label: axes name the quantity and its unit, read off the unit suffixes of channel and field names, never
// a bare JSON pointer or channel name.
#include "drillwave/io/axis_label.hpp"

#include <gtest/gtest.h>

namespace drillwave::io {
namespace {

TEST(AxisLabel, ChannelNamesGiveTheQuantityAndItsUnit) {
  EXPECT_EQ(AxisLabel(QuantityOfName("bit_rpm")), "bit speed [rpm]");
  EXPECT_EQ(AxisLabel(QuantityOfName("top_torque_Nm")), "top torque [N m]");
  EXPECT_EQ(AxisLabel(QuantityOfName("top_torque_kNm")), "top torque [kN m]");
  EXPECT_EQ(AxisLabel(QuantityOfName("hookload_kN")), "hookload [kN]");
  EXPECT_EQ(AxisLabel(QuantityOfName("tob_Nm")), "torque on bit [N m]");
  EXPECT_EQ(AxisLabel(QuantityOfName("wob_N")), "weight on bit [N]");
  EXPECT_EQ(AxisLabel(QuantityOfName("bit_angle_rad")), "bit angle [rad]");
  EXPECT_EQ(AxisLabel(QuantityOfName("bit_speed_rad_s")), "bit speed [rad/s]");
  EXPECT_EQ(AxisLabel(QuantityOfName("time_s")), "time [s]");
  EXPECT_EQ(AxisLabel(QuantityOfName("bit_stuck")), "bit stuck");  // a flag: no unit to name
}

TEST(AxisLabel, FieldNamesWithCompoundUnitsAndSymbols) {
  EXPECT_EQ(AxisLabel(QuantityOfName("inertia_kgm2")), "inertia [kg m²]");
  EXPECT_EQ(AxisLabel(QuantityOfName("kp_Nms_per_rad")), "kp [N m s/rad]");
  EXPECT_EQ(AxisLabel(QuantityOfName("lateral_stiffness_N_per_m")), "lateral stiffness [N/m]");
  EXPECT_EQ(AxisLabel(QuantityOfName("density_kg_m3")), "density [kg/m³]");
  EXPECT_EQ(AxisLabel(QuantityOfName("T_s_Nm")), "T_s [N m]");
  EXPECT_EQ(AxisLabel(QuantityOfName("nu_f_rad_s")), "nu_f [rad/s]");
  // A Greek letter's subscript is not a unit: mu_s is the static friction coefficient, not a mu in seconds.
  EXPECT_EQ(AxisLabel(QuantityOfName("mu_s")), "mu_s");
  EXPECT_EQ(AxisLabel(QuantityOfName("R_m")), "R [m]");
}

TEST(AxisLabel, PointersNameTheFieldByTheObjectsAboveIt) {
  EXPECT_EQ(AxisLabel(QuantityOfPointer("/model/bit/inertia_kgm2")), "bit inertia [kg m²]");
  EXPECT_EQ(AxisLabel(QuantityOfPointer("/model/upper_disc/input_voltage_V")), "upper disc input voltage [V]");
  EXPECT_EQ(AxisLabel(QuantityOfPointer("/model/hoist/weight_on_bit_N")), "hoist weight on bit [N]");
  EXPECT_EQ(AxisLabel(QuantityOfPointer("/model/bit/friction/mu_s")), "bit friction mu_s");
  EXPECT_EQ(AxisLabel(QuantityOfPointer("/model/string/sections/0/length_m")), "string section 0 length [m]");
  EXPECT_EQ(AxisLabel(QuantityOfPointer("/simulation/duration_s")), "simulation duration [s]");
}

TEST(AxisLabel, AScheduleKnotIsItsValueOrItsTime) {
  EXPECT_EQ(AxisLabel(QuantityOfPointer("/model/top/speed_rad_s/knots/1/1")), "top speed at knot 1 [rad/s]");
  EXPECT_EQ(AxisLabel(QuantityOfPointer("/model/top/speed_rad_s/knots/4/0")), "top speed: time of knot 4 [s]");
}

TEST(AxisLabel, EscapedPointerSegmentsAreDecoded) {
  EXPECT_EQ(QuantityOfPointer("/model/a~1b_m").name, "a/b");
  EXPECT_EQ(QuantityOfPointer("/model/a~1b_m").unit, "m");
}

TEST(AxisLabel, ChannelsOfOneUnitShareIt) {
  EXPECT_EQ(AxisLabelOfChannels({"top_rpm", "bit_rpm"}), "top speed, bit speed [rpm]");
  EXPECT_EQ(AxisLabelOfChannels({"bit_rpm", "bit_torque_Nm"}), "bit speed [rpm], bit torque [N m]");
}

}  // namespace
}  // namespace drillwave::io
