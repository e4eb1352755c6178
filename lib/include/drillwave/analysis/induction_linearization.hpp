#pragma once
// The induction motor's flux equations and torque linearized about the fluxes psi0 that hold still at supply f0 and
// shaft speed wm0, by central differences of the model's own FluxRates and Torque (so they cannot drift from what the
// simulation integrates). These are exact up to rounding: the flux rates are affine in the fluxes and in the shaft
// speed (currents are linear in the fluxes), the torque is a quadratic form of the fluxes, and a central difference
// of a quadratic has no truncation error. The steps are therefore large (1e-4 of the scale), which keeps the rounding
// near 1e-12 relative. In the supply the rates are affine too except where the V/f line meets the voltage limit: the
// step stays within half the distance to that corner.
#include <Eigen/Dense>

#include "drillwave/model/induction_motor.hpp"

namespace drillwave::analysis {

struct InductionJacobian {
  Eigen::Matrix4d flux = Eigen::Matrix4d::Zero();          // d psi' / d psi
  Eigen::Vector4d supply_hz = Eigen::Vector4d::Zero();     // d psi' / d f
  Eigen::Vector4d shaft_speed = Eigen::Vector4d::Zero();   // d psi' / d w_m
  Eigen::RowVector4d torque = Eigen::RowVector4d::Zero();  // d T / d psi
};

InductionJacobian LinearizeInductionMotor(const model::InductionMotor& m, double f0, double wm0);

}  // namespace drillwave::analysis
