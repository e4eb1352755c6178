#pragma once
// The rig's two-mass top in closed form: a motor of (referred) inertia J_m behind a gear of stiffness k and damping c,
// driving a top inertia J that a string loads as a dashpot Z (exact while no wave has come back up the string, or
// for ever with a matched bit). Linear in the state y = (motor speed, gear twist, top speed):
//   J_m w_m' = T_m - k d - c (w_m - w),  d' = w_m - w,  J w' = k d + c (w_m - w) - Z w.
#include <algorithm>
#include <cmath>
#include <complex>

#include <Eigen/Eigenvalues>

namespace drillwave::testing {

struct TwoMassOnDashpot {
  double motor_inertia, stiffness, damping, top_inertia, dashpot;

  Eigen::Matrix3d Matrix() const {
    const double jm = motor_inertia, k = stiffness, c = damping, j = top_inertia;
    Eigen::Matrix3d a;
    a << -c / jm, -k / jm, c / jm,  //
        1, 0, -1,                   //
        c / j, k / j, -(c + dashpot) / j;
    return a;
  }
  // y(t) from y(0) = y0 under a constant motor torque T_m: exp(A t) (y0 + A^-1 f) - A^-1 f, f = (T_m / J_m, 0, 0),
  // exp(A t) from the eigen-decomposition of A.
  Eigen::Vector3d Response(double t, const Eigen::Vector3d& y0, double motor_torque) const {
    const Eigen::Matrix3d a = Matrix();
    const Eigen::Vector3d shift = a.lu().solve(Eigen::Vector3d(motor_torque / motor_inertia, 0, 0));
    const Eigen::EigenSolver<Eigen::Matrix3d> eig(a);
    const Eigen::Vector3cd coeff = eig.eigenvectors().lu().solve((y0 + shift).cast<std::complex<double>>());
    const Eigen::Vector3cd modes = (eig.eigenvalues() * t).array().exp() * coeff.array();
    return (eig.eigenvectors() * modes).real() - shift;
  }
  // The two-mass mode: imaginary part of A's complex eigenvalues, and its undamped closed form sqrt(k (1/J_m + 1/J)).
  double DampedFrequency() const {
    const Eigen::EigenSolver<Eigen::Matrix3d> eig(Matrix());
    double w = 0;
    for (int k = 0; k < 3; ++k) w = std::max(w, eig.eigenvalues()(k).imag());
    return w;
  }
  double UndampedFrequency() const { return std::sqrt(stiffness * (1 / motor_inertia + 1 / top_inertia)); }
  double GearTorque(const Eigen::Vector3d& y) const { return stiffness * y(1) + damping * (y(0) - y(2)); }
};

}  // namespace drillwave::testing
