// The bounded minimizer behind the fits: a known minimum inside the cube and on its edge, the budget kept, starts side
// by side as one after the other, and the curvature's sigma against a quadratic's exact one.
#include <atomic>
#include <cmath>

#include <gtest/gtest.h>

#include "drillwave/diagnosis/minimize.hpp"

namespace drillwave::diagnosis {
namespace {

TEST(Minimize, FindsAQuadraticsMinimumInsideAndOnTheEdge) {
  int calls = 0;
  auto bowl = [&](const std::vector<double>& u) {
    ++calls;
    return 100 * std::pow(u[0] - 0.3, 2) + 40 * std::pow(u[1] - 0.8, 2) + 2;
  };
  MinimizeOptions o;
  o.max_evaluations = 200;
  const MinimizeResult r = MinimizeInUnitCube(bowl, {0.9, 0.1}, o);
  EXPECT_NEAR(r.best[0], 0.3, 0.02);
  EXPECT_NEAR(r.best[1], 0.8, 0.02);
  EXPECT_NEAR(r.value, 2, 0.05);
  EXPECT_LE(r.evaluations, 200);
  EXPECT_EQ(r.evaluations, calls);
  // The minimum outside the cube: the search stops on its face.
  auto outside = [](const std::vector<double>& u) { return std::pow(u[0] - 1.5, 2); };
  EXPECT_NEAR(MinimizeInUnitCube(outside, {0.2}, o).best[0], 1.0, 1e-3);
}

TEST(Minimize, KeepsItsBudgetAndEvaluatesOnceWithoutParameters) {
  int calls = 0;
  auto f = [&](const std::vector<double>& u) {
    ++calls;
    return std::sin(20 * u[0]) + u[0];
  };
  MinimizeOptions o;
  o.max_evaluations = 12;
  EXPECT_LE(MinimizeInUnitCube(f, {0.5}, o).evaluations, 12);
  EXPECT_LE(calls, 12);
  calls = 0;
  EXPECT_EQ(MinimizeInUnitCube([&](const std::vector<double>&) { return ++calls, 3.0; }, {}, o).evaluations, 1);
  EXPECT_EQ(calls, 1);
}

// Each start has its own share of the budget and its own seeded point, so running them side by side changes nothing:
// the same best point, value and evaluations, with a multimodal function whose starts end in different valleys.
TEST(Minimize, StartsSideBySideGiveTheSameResultAsOneAfterTheOther) {
  std::atomic<int> calls{0};
  auto wavy = [&](const std::vector<double>& u) {
    ++calls;
    return std::sin(17 * u[0]) * std::cos(11 * u[1]) + 0.3 * u[0];
  };
  MinimizeOptions o;
  o.max_evaluations = 61;
  o.starts = 4;
  const MinimizeResult one = MinimizeInUnitCube(wavy, {0.5, 0.5}, o);
  const int calls_one = calls.exchange(0);
  o.threads = 2;
  const MinimizeResult two = MinimizeInUnitCube(wavy, {0.5, 0.5}, o);
  EXPECT_EQ(one.best, two.best);
  EXPECT_EQ(one.value, two.value);
  EXPECT_EQ(one.evaluations, two.evaluations);
  EXPECT_EQ(calls.load(), calls_one);
  EXPECT_EQ(one.evaluations, calls_one);
  EXPECT_LE(one.evaluations, 61);
  EXPECT_GT(one.evaluations, 30);  // the four starts used their shares (15 each, after the first point)
}

TEST(Minimize, CurvatureSigmaOfAQuadraticIsExact) {
  // chi2 = weight * f with f = a (u - c)^2: d2chi2 = 2 weight a, sigma = sqrt(2 / (2 weight a)) = 1/sqrt(weight a).
  const double a = 50, weight = 4;
  auto f = [&](const std::vector<double>& u) { return a * std::pow(u[0] - 0.5, 2) + 1 + 0 * u[1]; };
  const std::vector<double> sigma = CurvatureSigma(f, {0.5, 0.99}, 1.0, weight);
  EXPECT_NEAR(sigma[0], 1 / std::sqrt(weight * a), 1e-9);
  EXPECT_TRUE(std::isnan(sigma[1]));  // flat along u[1]: not identified (and at the edge: stepped inwards)
}

}  // namespace
}  // namespace drillwave::diagnosis
