// Event detection of the Simulator loop on a process small enough to solve by hand.
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "drillwave/integration/simulator.hpp"

namespace {

using drillwave::integration::IntegratorOptions;
using drillwave::integration::Piece;
using drillwave::integration::Simulator;

// What every small process below shares: no delays (no step limit), nothing to prepare or store per piece, no
// breakpoints.
struct PlainProcess {
  double MaxStep() const { return std::numeric_limits<double>::infinity(); }
  void BeginStep(double) {}
  double PrepareCommit(const Piece&, double, double) { return 0; }
  void Commit(const Piece&) {}
  double NextBreakpoint() const { return std::numeric_limits<double>::infinity(); }
  void OnBreakpoint(double) {}
};

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

// Two modes that hand over to each other every 4e-11 s (x' = -1 until x = -h, then +1 until x = +h, h = 2e-11): no
// two events at the same instant, yet no time passes. The loop must stop with the time and the state, not store
// pieces for ever (the coupled bit's stuck-lifted-dropped cycle of issue 41 did so until memory ran out).
class Chatter : public PlainProcess {
 public:
  int Dimension() const { return 1; }
  void Derivatives(const std::vector<double>&, std::vector<double>& dxdt, double) const {
    dxdt[0] = mode_ == 0 ? -1.0 : 1.0;
  }
  void Commit(const Piece&) { ++commits_; }
  int NumWitnesses() const { return 1; }
  double Witness(int, double, const std::vector<double>& x) const { return mode_ == 0 ? x[0] + kH : kH - x[0]; }
  bool OnEvent(int, double, std::vector<double>&) {
    mode_ = 1 - mode_;
    return true;
  }
  long commits() const { return commits_; }

 private:
  static constexpr double kH = 2e-11;
  int mode_ = 0;
  long commits_ = 0;
};

TEST(SimulatorEvents, ModesChatteringOnAVanishingTimeScaleStopTheRunWithTimeAndState) {
  Chatter process;
  IntegratorOptions options;
  options.event_time_tol = 1e-15;
  options.max_steps = 1000000;  // without the guard the run ends here, a million pieces on
  Simulator<Chatter> sim(process, options);
  try {
    sim.Integrate(0.0, {1.0}, 2.0);
    FAIL() << "the chattering run ended normally";
  } catch (const drillwave::NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("chattering"), std::string::npos) << e.what();
    EXPECT_NEAR(e.time(), 1.0, 1e-6);
    EXPECT_LT(process.commits(), 1000);
  }
}

// x' = 10 x escapes to infinity without any step-size trouble (a delayed feedback loop without a limit did, to
// 1e33 rpm, for 2.4 million stored steps and 3 GB): stopped once it has grown 1e12 times, at ln(1e12) / 10 = 2.76 s.
class Growth : public PlainProcess {
 public:
  int Dimension() const { return 1; }
  void Derivatives(const std::vector<double>& x, std::vector<double>& dxdt, double) const { dxdt[0] = 10 * x[0]; }
  int NumWitnesses() const { return 0; }
  double Witness(int, double, const std::vector<double>&) const { return 1.0; }
  bool OnEvent(int, double, std::vector<double>&) { return false; }
};

TEST(SimulatorGrowth, ASolutionEscapingToInfinityIsStoppedWhenItHasGrownATrillionTimes) {
  Growth process;
  IntegratorOptions options;
  options.abs_tol = options.rel_tol = 1e-8;
  Simulator<Growth> sim(process, options);
  try {
    sim.Integrate(0.0, {1.0}, 100.0);
    FAIL() << "not stopped";
  } catch (const drillwave::NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("blow-up"), std::string::npos) << e.what();
    EXPECT_NEAR(e.time(), std::log(1e12) / 10, 0.05);
  }
}

}  // namespace
