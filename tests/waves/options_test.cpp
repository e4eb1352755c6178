// NetworkRunOptions::IsValid (core/validity.hpp): the defaults pass, each field out of its range is named, an
// integrator field through the integrator; SimulateNetwork refuses them with a ParameterError before it looks at the
// network.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "drillwave/waves/network_simulation.hpp"
#include "invalid_field.hpp"

namespace drillwave::waves {
namespace {

using testing::InvalidField;
using testing::InvalidFieldWith;
using testing::RefusedParameter;

TEST(NetworkRunOptions, TheDefaultsAreValidAndEachBadFieldIsNamed) {
  const NetworkRunOptions o;
  EXPECT_EQ(InvalidField(o), "");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.t_end_s = 0; }), "t_end_s");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.output_interval_s = -1e-3; }), "output_interval_s");
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.output_interval_s = 0; }), "");  // the integrator's steps only
  EXPECT_EQ(InvalidFieldWith(o, [](auto& b) { b.integrator.rel_tol = std::nan(""); }), "integrator.rel_tol");
}

TEST(NetworkRunOptions, SimulateNetworkRefusesThemBeforeLookingAtTheNetwork) {
  NetworkRunOptions o;
  o.integrator.abs_tol = 0;
  EXPECT_EQ(RefusedParameter([&] { SimulateNetwork(Network{}, o); }), "integrator.abs_tol");
}

}  // namespace
}  // namespace drillwave::waves
