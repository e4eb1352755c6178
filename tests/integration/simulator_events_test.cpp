// Event detection of the Simulator loop on a process small enough to solve by hand.
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/integration/simulator.hpp"

namespace {

using drillwave::integration::IntegratorOptions;
using drillwave::integration::Piece;
using drillwave::integration::Simulator;

// x' = v(mode) with a witness g = x in mode 0 (moving down from where it starts) that switches to mode 1 (x' = +1)
// when x reaches 0 from above, or leaves it at once if x starts at exactly 0 and moves down.
class Descent {
 public:
  explicit Descent(double speed) : speed_(speed) {}
  int Dimension() const { return 1; }
  void Derivatives(const std::vector<double>&, std::vector<double>& dxdt, double) const {
    dxdt[0] = mode_ == 0 ? -speed_ : 1.0;
  }
  double MaxStep() const { return std::numeric_limits<double>::infinity(); }
  void BeginStep(double) {}
  double PrepareCommit(const Piece&, double, double) { return 0; }
  void Commit(const Piece&) {}
  int NumWitnesses() const { return 1; }
  double Witness(int, double, const std::vector<double>& x) const { return mode_ == 0 ? x[0] : 1.0; }
  bool OnEvent(int, double t, std::vector<double>&) {
    mode_ = 1;
    event_time_ = t;
    return true;
  }
  double NextBreakpoint() const { return std::numeric_limits<double>::infinity(); }
  void OnBreakpoint(double) {}

  double event_time() const { return event_time_; }

 private:
  double speed_;
  int mode_ = 0;
  double event_time_ = std::numeric_limits<double>::quiet_NaN();
};

TEST(SimulatorEvents, WitnessCrossingZeroFromAboveIsLocated) {
  Descent process(2.0);
  Simulator<Descent> sim(process, IntegratorOptions{});
  const auto x = sim.Integrate(0.0, {1.0}, 2.0);
  EXPECT_NEAR(process.event_time(), 0.5, 1e-11);
  EXPECT_NEAR(x[0], 1.5, 1e-9);  // 0 at t = 0.5, then +1 for 1.5 s
  EXPECT_EQ(sim.stats().events, 1);
}

// A witness left at exactly 0 by a restart (a slip regime entered at zero speed) that then goes negative must fire:
// the rule "> 0 to <= 0" alone would miss it and keep the wrong regime until the next breakpoint.
TEST(SimulatorEvents, WitnessStartingAtExactlyZeroAndGoingNegativeFires) {
  Descent process(2.0);
  Simulator<Descent> sim(process, IntegratorOptions{});
  const auto x = sim.Integrate(0.0, {0.0}, 1.0);
  EXPECT_LT(process.event_time(), 1e-9);
  EXPECT_NEAR(x[0], 1.0, 1e-9);
  EXPECT_EQ(sim.stats().events, 1);
}

// A stiff state (x' = -5000 (x - cos t), as a motor current with La/R = 0.2 ms) whose steps the explicit method
// keeps at its stability limit, where the cubic history interpolant misses the state's own midpoint; with a history
// step floor above every step such pieces are accepted as they are, and must still have been prepared
// (PrepareCommit) before they are committed.
class StiffRelaxation {
 public:
  int Dimension() const { return 1; }
  void Derivatives(const std::vector<double>& x, std::vector<double>& dxdt, double t) const {
    dxdt[0] = -5000 * (x[0] - std::cos(t));
  }
  double MaxStep() const { return std::numeric_limits<double>::infinity(); }
  void BeginStep(double) {}
  double PrepareCommit(const Piece& p, double, double) {
    prepared_t0_ = p.t0, prepared_t1_ = p.t1;
    return 0;
  }
  void Commit(const Piece& p) {
    ++commits_;
    if (p.t0 != prepared_t0_ || p.t1 != prepared_t1_) ++unprepared_;
  }
  int NumWitnesses() const { return 0; }
  double Witness(int, double, const std::vector<double>&) const { return 1.0; }
  bool OnEvent(int, double, std::vector<double>&) { return false; }
  double NextBreakpoint() const { return std::numeric_limits<double>::infinity(); }
  void OnBreakpoint(double) {}

  int commits() const { return commits_; }
  int unprepared() const { return unprepared_; }

 private:
  double prepared_t0_ = -1, prepared_t1_ = -1;
  int commits_ = 0, unprepared_ = 0;
};

TEST(SimulatorHistory, EveryPieceAcceptedBelowTheFloorIsPreparedBeforeItsCommit) {
  StiffRelaxation process;
  IntegratorOptions options;
  options.abs_tol = options.rel_tol = 1e-7;
  options.history_step_floor = 1e9;
  Simulator<StiffRelaxation> sim(process, options);
  sim.Integrate(0.0, {1.0}, 1.0);
  EXPECT_GT(process.commits(), 10);
  EXPECT_EQ(process.unprepared(), 0) << "of " << process.commits() << " pieces";
}

}  // namespace
