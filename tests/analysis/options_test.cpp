// The analysis options' IsValid (core/validity.hpp): the defaults pass, each field out of its range is named (a
// shooting field inside the continuation's through it); shooting, continuation and the spectrum refuse them with a
// ParameterError naming the field before any flow or root is computed.
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "drillwave/analysis/periodic_orbits.hpp"
#include "drillwave/analysis/spectrum.hpp"
#include "invalid_field.hpp"

namespace drillwave::analysis {
namespace {

using testing::InvalidField;
using testing::InvalidFieldWith;
using testing::RefusedParameter;

const double kNaN = std::nan(""), kInf = std::numeric_limits<double>::infinity();

// x' = -x: enough of a field to be handed to the shooting.
class Decay : public PiecewiseSmoothField {
 public:
  int Dimension() const override { return 1; }
  Eigen::VectorXd Derivatives(int, const Eigen::VectorXd& x) const override { return -x; }
};

TEST(ShootingOptions, TheDefaultsAreValidAndEachBadFieldIsNamed) {
  const ShootingOptions o;
  EXPECT_EQ(InvalidField(o), "");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.abs_tol = 0; }), "abs_tol");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.rel_tol = kNaN; }), "rel_tol");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.newton_tol = -1; }), "newton_tol");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.max_newton = 0; }), "max_newton");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.samples_per_period = 0; }), "samples_per_period");
}

TEST(ContinuationOptions, TheDefaultsAreValidAndEachBadFieldIsNamed) {
  const ContinuationOptions o;
  EXPECT_EQ(InvalidField(o), "");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.p_min = 2, b.p_max = 1; }), "p_max");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.min_step = 0; }), "min_step");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.initial_step = 1e-6; }), "initial_step");  // below min_step
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.max_step = 0.01; }), "max_step");          // below initial_step
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.max_step = kInf; }), "max_step");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.p_scale = 0; }), "p_scale");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.max_points = 0; }), "max_points");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.hopf_amplitude = 0; }), "hopf_amplitude");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.end_amplitude = -1; }), "end_amplitude");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.amplitude_component = -2; }), "amplitude_component");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.dp_fd = 0; }), "dp_fd");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.shooting.abs_tol = 0; }), "shooting.abs_tol");
}

TEST(SpectrumOptions, TheDefaultsAreValidAndEachBadFieldIsNamed) {
  const SpectrumOptions o;
  EXPECT_EQ(InvalidField(o), "");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.collocation_nodes = 3; }), "collocation_nodes");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.re_min = -kInf; }), "re_min");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.im_max = 0; }), "im_max");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.newton_iterations = 0; }), "newton_iterations");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.root_tolerance = kNaN; }), "root_tolerance");
}

TEST(AnalysisOptions, ShootingContinuationAndTheSpectrumRefuseThemBeforeAnyWork) {
  const Decay decay;
  ShootingOptions shooting;
  shooting.newton_tol = 0;
  const Eigen::VectorXd x = Eigen::VectorXd::Ones(1);
  EXPECT_EQ(RefusedParameter([&] { Flow(decay, x, 1, false, shooting); }), "newton_tol");
  EXPECT_EQ(RefusedParameter([&] { FindPeriodicOrbit(decay, x, 1, shooting); }), "newton_tol");
  ContinuationOptions continuation;
  continuation.p_min = 2, continuation.p_max = 1;
  const FieldFamily family = [](double) { return std::make_shared<Decay>(); };
  EXPECT_EQ(RefusedParameter([&] { ContinueFromHopf(family, HopfPoint{}, continuation); }), "p_max");
  SpectrumOptions spectrum;
  spectrum.collocation_nodes = 3;
  const LinearDelaySystem system{Eigen::MatrixXd::Constant(1, 1, -1.0), {}};
  EXPECT_EQ(RefusedParameter([&] { ComputeSpectrum(system, spectrum); }), "collocation_nodes");
}

}  // namespace
}  // namespace drillwave::analysis
