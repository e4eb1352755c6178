// The wave network's linearization holds the top drive as the component the simulation runs (dynamics::TopDrive):
// the rows of the drive's own states (the PI's integral, a DC motor's current, an induction motor's fluxes, a
// compliant gear's motor speed and twist) are the component's rates differentiated by central differences about the
// steady start, for the drive's states and the node's speed.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/analysis/network_linearization.hpp"
#include "drillwave/waves/network_simulation.hpp"
#include "drive_rows.hpp"
#include "equivalent_circuit.hpp"

namespace drillwave::analysis {
namespace {

using model::Drive;
using Side = integration::Side;

waves::Network StringWithTop(Drive drive, bool compliant_gear) {
  waves::Network net;
  net.sections.push_back(waves::Section::Torsional(1500, 79.3e9, 8000, 1.19e-5));
  waves::Node top;
  top.name = "top";
  top.inertia = 900;
  top.drive = drive;
  top.pi = {drive == Drive::kDcMotorSpeed ? 40.0 : 3.0e4, drive == Drive::kDcMotorSpeed ? 60.0 : 4.0e4};
  top.setpoint = model::Schedule(6.0);
  top.motor = {35.0, 0.04, 0.01, 0.0};
  top.induction = testing::IllustrativeMachine();
  top.gear.ratio = drive == Drive::kInductionMotorSpeed ? 8.0 : drive == Drive::kDcMotorSpeed ? 2.0 : 1.0;
  if (compliant_gear) top.gear.stiffness = 4e5, top.gear.damping = 900, top.gear.motor_inertia = 15;
  waves::Node bit;
  bit.name = "bit";
  bit.inertia = 300;
  bit.ground_damping = 600;  // the load the top carries
  net.nodes = {top, bit};
  net.initial.speed_rad_s = 6.0;
  return net;
}

int Index(const NetworkLinearization& lin, const std::string& name) {
  const auto it = std::find(lin.state_names.begin(), lin.state_names.end(), name);
  return it == lin.state_names.end() ? -1 : static_cast<int>(it - lin.state_names.begin());
}

// The largest difference between the linearization's drive rows and the component's differentiated rates, relative
// to each row's largest entry.
double WorstRowDifference(Drive drive, bool compliant_gear, int& compared) {
  const waves::Network net = StringWithTop(drive, compliant_gear);
  const std::vector<NetworkOperatingPoint> points = NetworkSteadyStates(net);
  EXPECT_EQ(points.size(), 1u);
  if (points.empty()) return 1.0;
  const NetworkOperatingPoint& p = points.front();
  const NetworkLinearization lin = LinearizeNetwork(net, p);
  const waves::Node& top = net.top();
  const dynamics::TopDriveParts parts = waves::DriveParts(top);  // as the simulation builds it from the node
  dynamics::TopDrive::Slots slots;
  slots.integral = Index(lin, "top_speed_error_integral_rad");
  slots.current = Index(lin, "top_current_A");
  slots.flux = Index(lin, "top_stator_flux_d_Wb");
  slots.motor_speed = Index(lin, "top_motor_speed_referred_rad_s");
  const int speed = Index(lin, "top_speed_rad_s");
  EXPECT_GE(slots.integral, 0);
  EXPECT_GE(speed, 0);
  const dynamics::TopDrive component(parts, slots, p.speed_rad_s, p.top_torque_Nm);
  std::vector<double> x(lin.system.dimension(), 0.0);
  component.SteadyStart(p.top_torque_Nm - top.SteadyLoad(p.speed_rad_s), x);
  x[speed] = p.speed_rad_s;
  return testing::WorstDriveRowDifference(lin.system, component, slots, speed, x, compared);
}

TEST(TopDriveLinearization, NetworkRowsAreTheComponentsRatesDifferentiated) {
  struct Kind {
    const char* name;
    Drive drive;
    bool compliant_gear;
  };
  for (const Kind& k : {Kind{"PI behind a compliant gear", Drive::kPiSpeedController, true},
                        Kind{"DC motor, PI in volts", Drive::kDcMotorSpeed, false},
                        Kind{"DC motor behind a compliant gear", Drive::kDcMotorSpeed, true},
                        Kind{"induction motor, slip-frequency speed loop", Drive::kInductionMotorSpeed, false}}) {
    int compared = 0;
    const double worst = WorstRowDifference(k.drive, k.compliant_gear, compared);
    std::cout << "[ measured ] " << k.name << ": " << compared << " entries, largest difference " << worst
              << " of the row's largest\n";
    EXPECT_LT(worst, 1e-6) << k.name;
    EXPECT_GE(compared, 4) << k.name;
  }
}

}  // namespace
}  // namespace drillwave::analysis
