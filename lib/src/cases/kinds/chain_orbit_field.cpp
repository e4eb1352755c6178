// A lumped chain (lumped_friction_process.hpp) at its inputs' final values as a piecewise-smooth autonomous field,
// for periodic orbits and their continuation (analysis/periodic_orbits.hpp). State: the twists, the speeds of the
// inertias that move freely, the PI integral (the layout of LinearizeChain). Mode: the regime of every inertia that
// can stick (a bitrock::Turn as its integer: +1 / -1 slipping, 0 stuck), with the switches of bitrock/stick_slip.hpp: a slipping inertia
// stops when its speed in the slip direction reaches 0; a stuck one breaks free when the torque on it leaves its
// static range. While stuck its speed is held at 0, so a stick-slip cycle's monodromy has a zero multiplier.
#include <cmath>
#include <limits>

#include "drillwave/bitrock/stick_slip.hpp"
#include "drillwave/dynamics/contact.hpp"
#include "lumped_friction_process.hpp"

namespace drillwave::cases::lumped {
namespace {

class ChainField : public analysis::PiecewiseSmoothField {
 public:
  explicit ChainField(Chain c) : c_(std::move(c)), n_(static_cast<int>(c_.inertias.size())) {
    c_.Validate();
    u_ = c_.setpoint.knots().back().second;
    speed_index_.assign(n_, -1);
    int next = n_ - 1;
    for (int i = Prescribed() ? 1 : 0; i < n_; ++i) speed_index_[i] = next++;
    integral_ = c_.drive == Drive::kPiSpeed ? next++ : -1;
    dim_ = next;
    for (int i = 0; i < n_; ++i) {
      const auto& f = c_.inertias[i].friction;
      if (f && Contact(i).CanStick() && speed_index_[i] >= 0) frictional_.push_back(i);
      scale_.push_back(c_.inertias[i].friction_scale.knots().back().second);
    }
  }

  int Dimension() const override { return dim_; }

  Eigen::VectorXd Derivatives(int mode, const Eigen::VectorXd& x) const override {
    Eigen::VectorXd dx(dim_);
    for (int j = 0; j + 1 < n_; ++j) dx[j] = Speed(mode, j, x) - Speed(mode, j + 1, x);
    for (int i = 0; i < n_; ++i) {
      if (speed_index_[i] < 0) continue;
      const int r = Regime(mode, i);
      const double v = Speed(mode, i, x);
      dx[speed_index_[i]] =
          r == 0 ? 0.0 : (Unbalanced(mode, i, x, v) - Friction(i, v, r)) / c_.inertias[i].inertia_kgm2;
    }
    if (integral_ >= 0) {
      const double error = u_ - Speed(mode, 0, x);
      dx[integral_] = c_.DriveIntegralHeld(c_.pi.Output(u_, Speed(mode, 0, x), x[integral_]), error) ? 0.0 : error;
    }
    return dx;
  }

  int ModeAt(const Eigen::VectorXd& x) const override {
    int mode = 0;  // every regime +1 is code 2 per digit; build it digit by digit
    std::vector<int> regimes(frictional_.size(), 1);
    for (std::size_t k = 0; k < frictional_.size(); ++k) {
      const double v = x[speed_index_[frictional_[k]]];
      regimes[k] = v > 0 ? 1 : v < 0 ? -1 : 0;
    }
    mode = Encode(regimes);
    // At rest: stuck unless the torque already exceeds the static range.
    for (std::size_t k = 0; k < frictional_.size(); ++k)
      if (regimes[k] == 0) {
        regimes[k] = static_cast<int>(bitrock::TurnAtRest(AtRest(mode, frictional_[k], x)));
        mode = Encode(regimes);
      }
    return mode;
  }

  int NumSwitches() const override { return 2 * static_cast<int>(frictional_.size()); }

  double Switch(int mode, int k, const Eigen::VectorXd& x) const override {
    const int i = frictional_[k / 2];
    return bitrock::TurnWitness(static_cast<bitrock::Turn>(Regime(mode, i)), k % 2, x[speed_index_[i]],
                                [&] { return AtRest(mode, i, x); });
  }

  int ModeAfter(int mode, int k, const Eigen::VectorXd& x) const override {
    const int slot = k / 2, i = frictional_[slot];
    std::vector<int> regimes = Decode(mode);
    const auto before = static_cast<bitrock::Turn>(regimes[slot]);
    regimes[slot] = static_cast<int>(bitrock::TurnAfterEvent(before, k % 2, [&] {
      regimes[slot] = 0;
      return AtRest(Encode(regimes), i, x);
    }));
    return Encode(regimes);
  }

  void Project(int mode, Eigen::VectorXd& x) const override {
    for (int i : frictional_)
      if (Regime(mode, i) == 0) x[speed_index_[i]] = 0;
  }

  std::vector<Eigen::VectorXd> Equilibria() const override {
    std::vector<Eigen::VectorXd> out;
    for (const LinearizedOperatingPoint& p : LinearizeChain(c_)) {
      Eigen::VectorXd x = Eigen::VectorXd::Zero(dim_);
      const auto twists = p.steady_state.at("twists_rad").get<std::vector<double>>();
      for (int j = 0; j + 1 < n_; ++j) x[j] = twists[j];
      const double w = p.steady_state.at("speed_rad_s").get<double>();
      for (int i = 0; i < n_; ++i)
        if (speed_index_[i] >= 0) x[speed_index_[i]] = w;
      if (integral_ >= 0) x[integral_] = c_.pi.IntegralHolding(p.steady_state.at("drive_torque_Nm").get<double>());
      out.push_back(x);
    }
    return out;
  }

 private:
  bool Prescribed() const { return c_.drive == Drive::kPrescribedSpeed; }

  // Mode code: base-3 digits (regime + 1) of the frictional inertias, in order.
  int Encode(const std::vector<int>& regimes) const {
    int code = 0;
    for (std::size_t k = regimes.size(); k-- > 0;) code = 3 * code + regimes[k] + 1;
    return code;
  }
  std::vector<int> Decode(int mode) const {
    std::vector<int> r(frictional_.size());
    for (auto& v : r) v = mode % 3 - 1, mode /= 3;
    return r;
  }
  int Regime(int mode, int i) const {
    for (std::size_t k = 0; k < frictional_.size(); ++k, mode /= 3)
      if (frictional_[k] == i) return mode % 3 - 1;
    return 1;  // cannot stick: always "slipping"
  }

  double Speed(int mode, int i, const Eigen::VectorXd& x) const {
    if (speed_index_[i] < 0) return u_;
    return Regime(mode, i) == 0 ? 0.0 : x[speed_index_[i]];
  }
  // Inertia i's contact with its friction law (which it must have).
  dynamics::Contact Contact(int i) const {
    return dynamics::Contact(*c_.inertias[i].friction, c_.friction_smoothing_rad_s);
  }
  // The friction on inertia i slipping in regime r (+1 or -1) at v.
  double Friction(int i, double v, int r) const {
    if (!c_.inertias[i].friction) return 0;
    return Contact(i).SlipTorque(r > 0 ? bitrock::Turn::kForward : bitrock::Turn::kBackward, v, scale_[i]);
  }
  // Every torque on inertia i except its friction, its speed taken as v.
  double Unbalanced(int mode, int i, const Eigen::VectorXd& x, double v) const {
    double torque = -c_.inertias[i].damping_Nms_per_rad * v;
    if (i == 0) {
      if (c_.drive == Drive::kTorque) torque += c_.torque_gain * u_;
      if (c_.drive == Drive::kPiSpeed) torque += c_.ClampedDriveTorque(c_.pi.Output(u_, v, x[integral_]));
    }
    if (i > 0) {
      const Coupling& cp = c_.couplings[i - 1];
      torque += cp.stiffness_Nm_per_rad * x[i - 1] + cp.damping_Nms_per_rad * (Speed(mode, i - 1, x) - v);
    }
    if (i + 1 < n_) {
      const Coupling& cp = c_.couplings[i];
      torque -= cp.stiffness_Nm_per_rad * x[i] + cp.damping_Nms_per_rad * (v - Speed(mode, i + 1, x));
    }
    return torque;
  }
  // The torque on inertia i held at rest in `mode` and the static range of its (scaled) friction.
  bitrock::AtRest AtRest(int mode, int i, const Eigen::VectorXd& x) const {
    return Contact(i).HeldAtRest(Unbalanced(mode, i, x, 0.0), scale_[i]);
  }

  Chain c_;
  int n_;
  double u_ = 0;
  std::vector<int> speed_index_;
  int integral_ = -1;
  int dim_ = 0;
  std::vector<int> frictional_;
  std::vector<double> scale_;
};

}  // namespace

std::shared_ptr<const analysis::PiecewiseSmoothField> ChainOrbitField(const Chain& chain) {
  return std::make_shared<ChainField>(chain);
}

}  // namespace drillwave::cases::lumped
