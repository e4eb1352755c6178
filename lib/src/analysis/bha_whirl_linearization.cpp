#include "drillwave/analysis/bha_whirl_linearization.hpp"

#include <complex>
#include <string>

namespace drillwave::analysis {
namespace {

// A copy of m with `count` zero rows and columns inserted before index `at` (an empty matrix stays empty).
Eigen::MatrixXd WithStatesInserted(const Eigen::MatrixXd& m, int at, int count) {
  if (m.size() == 0) return m;
  const int n = static_cast<int>(m.rows()), tail = n - at;
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(n + count, n + count);
  out.topLeftCorner(at, at) = m.topLeftCorner(at, at);
  out.topRightCorner(at, tail) = m.topRightCorner(at, tail);
  out.bottomLeftCorner(tail, at) = m.bottomLeftCorner(tail, at);
  out.bottomRightCorner(tail, tail) = m.bottomRightCorner(tail, tail);
  return out;
}

}  // namespace

void AddBhaWhirl(NetworkLinearization& lin, int bit_speed, double row_inertia, double own_inertia,
                 const model::JeffcottBha& bha, double w0) {
  LinearDelaySystem& sys = lin.system;
  const int at = sys.dimension() - sys.derivative_only_states;
  sys.a0 = WithStatesInserted(sys.a0, at, 4);
  for (DelayTerm& d : sys.delays) {
    d.retarded = WithStatesInserted(d.retarded, at, 4);
    d.neutral = WithStatesInserted(d.neutral, at, 4);
  }
  const char* names[] = {"bit_whirl_xi_m", "bit_whirl_eta_m", "bit_whirl_xi_speed_m_s", "bit_whirl_eta_speed_m_s"};
  lin.state_names.insert(lin.state_names.begin() + at, std::begin(names), std::end(names));
  const int xi = at, eta = at + 1, dxi = at + 2, deta = at + 3, w = bit_speed;
  const int n = sys.dimension();

  const double mt = bha.TotalMass(), me = bha.Moment(), c = bha.damping, k = bha.stiffness;
  const std::complex<double> zeta0 = me * w0 * w0 / std::complex<double>(k - mt * w0 * w0, c * w0);
  const double a = zeta0.real(), b = zeta0.imag(), stiffness = k - mt * w0 * w0;
  // Mass matrix of (xi'', eta'', omega') in the rows (xi, eta, bit): the real and imaginary parts of the lateral
  // equation and the bit's torque balance.
  Eigen::Matrix3d mass;
  mass << mt, 0, -mt * b,
          0, mt, mt * a + me,
          0, me, own_inertia + me * bha.eccentricity + me * a;
  const Eigen::Matrix3d inverse = mass.inverse();
  // Right-hand sides: the bit's row in torque, then the lateral forces and the bit's whirl torque (A_0 only).
  auto transform = [&](Eigen::MatrixXd& m, bool with_whirl) {
    if (m.size() == 0) return;
    Eigen::MatrixXd force = Eigen::MatrixXd::Zero(3, n);
    force.row(2) = row_inertia * m.row(w);
    if (with_whirl) {
      force(0, xi) = -stiffness, force(0, eta) = c * w0, force(0, dxi) = -c, force(0, deta) = 2 * mt * w0;
      force(0, w) += 2 * mt * w0 * a + c * b + 2 * me * w0;
      force(1, xi) = -c * w0, force(1, eta) = -stiffness, force(1, dxi) = -2 * mt * w0, force(1, deta) = -c;
      force(1, w) += 2 * mt * w0 * b - c * a;
      force(2, dxi) += -2 * me * w0, force(2, eta) += me * w0 * w0, force(2, w) += 2 * me * w0 * b;
    }
    const Eigen::MatrixXd accelerations = inverse * force;
    m.row(dxi) = accelerations.row(0);
    m.row(deta) = accelerations.row(1);
    m.row(w) = accelerations.row(2);
  };
  transform(sys.a0, true);
  for (DelayTerm& d : sys.delays) {
    transform(d.retarded, false);
    transform(d.neutral, false);
  }
  sys.a0(xi, dxi) = 1;
  sys.a0(eta, deta) = 1;
}

}  // namespace drillwave::analysis
