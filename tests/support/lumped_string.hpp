#pragma once
// Independent reference for the torsional string: N lumped elements (inertia rho J L/N split to the element's two
// end nodes, spring G J N / L), dissipative top, bit inertia with set-valued Stribeck friction. An ODE without
// delays: it converges to the wave solution as N grows (O(1/N^2)), but its stiffness grows with N.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "drillwave/bitrock/friction.hpp"
#include "drillwave/integration/simulator.hpp"
#include "drillwave/model/schedule.hpp"

namespace drillwave::reference {

struct LumpedStringParams {
  double length_m = 1172, shear_modulus_pa = 79.3e9, density_kg_m3 = 8000, polar_moment_m4 = 1.19e-5;
  double beta = 2000, bit_inertia = 89;
  model::Schedule top_speed = model::Schedule({{0.0, 0.0}, {2.0, 10.0}});
  bitrock::FrictionLaw friction = bitrock::FrictionLaw(bitrock::Stribeck{97347, 0.155575, 0.5, 0.8, 0.9, 1.0, 0.03});
};

struct LumpedStringResult {
  double stick_slip_period_s = std::numeric_limits<double>::quiet_NaN();
  double stick_fraction = 0, bit_speed_mean = 0;
  integration::IntegrationStats stats;
};

// State: node speeds v_0..v_N, element twists theta_1..theta_N (phi_{j-1} - phi_j), bit angle.
class LumpedStringProcess {
 public:
  using State = std::vector<double>;
  LumpedStringProcess(const LumpedStringParams& p, int n) : p_(p), n_(n) {
    const double element_inertia = p.density_kg_m3 * p.polar_moment_m4 * p.length_m / n;
    inertia_.assign(n + 1, element_inertia);
    inertia_[0] = 0.5 * element_inertia;
    inertia_[n] = 0.5 * element_inertia + p.bit_inertia;
    stiffness_ = p.shear_modulus_pa * p.polar_moment_m4 * n / p.length_m;
  }
  int Dimension() const { return 2 * n_ + 2; }
  double MaxStep() const { return std::numeric_limits<double>::infinity(); }
  void BeginStep(double) {}
  double PrepareCommit(const integration::Piece&, double, double) { return 0; }
  void Commit(const integration::Piece&) {}
  int NumWitnesses() const { return 2; }

  double SpringTorque(const State& x, int element) const { return stiffness_ * x[n_ + element]; }  // element 1..N
  double DrivingTorqueOnBit(const State& x) const { return SpringTorque(x, n_); }

  void Derivatives(const State& x, State& dx, double t) const {
    for (int j = 0; j <= n_; ++j) {
      double torque = 0;
      if (j > 0) torque += SpringTorque(x, j);        // element above pulls forward
      if (j < n_) torque -= SpringTorque(x, j + 1);   // element below holds back
      if (j == 0) torque += p_.beta * (p_.top_speed.Value(t) - x[0]);
      if (j == n_) {
        if (regime_ == 0) {
          dx[j] = 0;
          continue;
        }
        torque -= p_.friction.SlipTorque(regime_ > 0 ? std::max(x[j], 1e-300) : std::min(x[j], -1e-300));
      }
      dx[j] = torque / inertia_[j];
    }
    for (int e = 1; e <= n_; ++e) dx[n_ + e] = x[e - 1] - (e == n_ && regime_ == 0 ? 0.0 : x[e]);
    dx[2 * n_ + 1] = regime_ == 0 ? 0.0 : x[n_];
  }
  double Witness(int i, double, const State& x) const {
    if (regime_ == 0) {
      const double drive = DrivingTorqueOnBit(x);
      return i == 0 ? p_.friction.StaticPositive() - drive : drive + p_.friction.StaticNegative();
    }
    return i == 0 ? regime_ * x[n_] : 1.0;
  }
  bool OnEvent(int i, double t, State& x) {
    const int before = regime_;
    if (regime_ == 0) {
      regime_ = i == 0 ? 1 : -1;
    } else {
      const double drive = DrivingTorqueOnBit(x);
      regime_ = drive > p_.friction.StaticPositive() ? 1 : (drive < -p_.friction.StaticNegative() ? -1 : 0);
    }
    if (regime_ == 0 || before == 0) x[n_] = 0;
    if (regime_ == 0 && before != 0) stick_onsets.push_back(t);
    if (regime_ != 0 && before == 0) releases.push_back(t);
    return regime_ != before;
  }
  double NextBreakpoint() const {
    for (const auto& k : p_.top_speed.knots())
      if (k.first > last_breakpoint_) return k.first;
    return std::numeric_limits<double>::infinity();
  }
  void OnBreakpoint(double t) { last_breakpoint_ = t; }

  std::vector<double> stick_onsets, releases;
  int regime_ = 0;  // starts stuck at rest

 private:
  const LumpedStringParams& p_;
  int n_;
  std::vector<double> inertia_;
  double stiffness_;
  double last_breakpoint_ = 0;
};

inline LumpedStringResult SimulateLumpedString(const LumpedStringParams& p, int n, double t_end, double window_begin,
                                               const integration::IntegratorOptions& options) {
  LumpedStringProcess process(p, n);
  integration::Simulator<LumpedStringProcess> sim(process, options);
  double angle_begin = 0;
  auto observer = [&](const integration::Piece& piece) {
    if (piece.t0 <= window_begin && piece.t1 > window_begin) {  // bit angle at the window start (linear is enough)
      const double w = (window_begin - piece.t0) / (piece.t1 - piece.t0);
      angle_begin = (1 - w) * piece.x0[2 * n + 1] + w * piece.x1[2 * n + 1];
    }
  };
  const auto x = sim.Integrate(0.0, std::vector<double>(2 * n + 2, 0.0), t_end, observer);
  LumpedStringResult r;
  r.stats = sim.stats();
  std::vector<double> onsets;
  for (double t : process.stick_onsets)
    if (t >= window_begin) onsets.push_back(t);
  if (onsets.size() >= 2) r.stick_slip_period_s = (onsets.back() - onsets.front()) / (onsets.size() - 1);
  double stuck = 0;
  for (std::size_t i = 0; i < process.stick_onsets.size(); ++i) {
    const double a = std::max(process.stick_onsets[i], window_begin);
    double release = t_end;
    for (double tr : process.releases)
      if (tr > process.stick_onsets[i]) {
        release = tr;
        break;
      }
    if (release > a) stuck += release - a;
  }
  r.stick_fraction = stuck / (t_end - window_begin);
  r.bit_speed_mean = (x[2 * n + 1] - angle_begin) / (t_end - window_begin);
  return r;
}

}  // namespace drillwave::reference
