#include "drillwave/bitrock/contact_law.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>

namespace drillwave::bitrock {
namespace {

// F is adimensional: the torsional laws' amplitude p, a torque there, must be 1.
bool IsUnitFunction(const FrictionLaw& f) {
  return std::visit(
      [](const auto& l) {
        using L = std::decay_t<decltype(l)>;
        if constexpr (std::is_same_v<L, SqrtRegularized> || std::is_base_of_v<TanhHump, L>) return l.amplitude == 1.0;
        return false;
      },
      f.law());
}

}  // namespace

ContactLaw::ContactLaw(const FrictionLaw& f, CuttingTorque cutting) : f_(f), cutting_(cutting) {
  if (!IsUnitFunction(f)) {
    const auto [key, value] = f.Values().front();  // a copy: Values() is a temporary
    throw std::invalid_argument("contact law: expected F as a sqrt_regularized, tanh_hump or tanh_hump_printed law "
                                "of amplitude_Nm 1 (F is adimensional), got " + f.Kind() + " with " + key + " = " +
                                std::to_string(value));
  }
}

// The laws are odd (F(|w|) sign w): their value at |w| is F.
double ContactLaw::F(double w) const { return f_ ? f_->SlipTorque(std::abs(w)) : 1.0; }

double ContactLaw::Slope(double w) const { return f_ ? f_->SlipTorqueDerivative(std::abs(w)) : 0.0; }

double ContactLaw::AtRest() const { return f_ ? f_->StaticPositive() : 1.0; }

double ContactLaw::CutTorque(double t_c, double w) const { return fades_cutting() ? t_c * CutFactor(w) : t_c; }

double ContactLaw::CutTorqueAtRest(double t_c) const {
  return fades_cutting() ? t_c * AtRest() * AtRest() : t_c;
}

double ContactLaw::CutTorqueSlope(double t_c, double w) const {
  return fades_cutting() ? t_c * 2 * F(w) * Slope(w) : 0.0;
}

}  // namespace drillwave::bitrock
