#include "drillwave/bitrock/friction.hpp"

#include <cmath>
#include <stdexcept>

#include "drillwave/core/error.hpp"
#include "drillwave/io/json_reader.hpp"

namespace drillwave::bitrock {
namespace {

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

double Sign(double w) { return w > 0 ? 1.0 : (w < 0 ? -1.0 : 0.0); }
// 1 - 2 / (1 + e^{a|w|}) = tanh(a|w| / 2): the smooth step of the humped law.
double Step(double a, double w) { return std::tanh(0.5 * a * std::abs(w)); }
double StepDerivative(double a, double w) {  // d/dw of Step, times sign(w) (the law multiplies by sign w)
  const double th = std::tanh(0.5 * a * std::abs(w));
  return 0.5 * a * (1 - th * th);
}

}  // namespace

double FrictionLaw::SlipTorque(double w) const {
  return std::visit(
      Overloaded{
          [w](const Viscous& l) { return l.c * w; },
          [w](const Coulomb& l) { return l.t_c * Sign(w) + l.c * w; },
          [w](const Stribeck& l) {
            return l.c_b * w + l.w_n * l.r_m * (l.mu_c + (l.mu_s - l.mu_c) * std::exp(-l.gamma_b * std::abs(w) / l.nu_f)) * Sign(w);
          },
          [w](const SqrtRegularized& l) { return l.amplitude * l.alpha * w / std::sqrt(w * w + l.epsilon * l.epsilon); },
          [w](const TanhHump& l) { return l.amplitude * l.beta * (std::tanh(w) + l.gamma1 * w / (1 + l.gamma2 * w * w)); },
          [w](const Rational& l) { return l.p * l.k * w / (l.k * l.k * w * w + l.zeta); },
          [w](const Humped& l) {
            const double magnitude = l.t_sl + l.t_1 * Step(l.omega_1, w) + l.t_2 * Step(l.omega_2, w) + l.b_l * std::abs(w);
            return magnitude * Sign(w) + l.delta_t_sl;
          },
          [w](const AsymmetricCoulombViscous& l) {
            return w > 0 ? (l.t_s + l.delta_t_s) + (l.b + l.delta_b) * w
                         : (w < 0 ? -(l.t_s - l.delta_t_s) + (l.b - l.delta_b) * w : 0.0);
          },
      },
      law_);
}

double FrictionLaw::SlipTorqueDerivative(double w) const {
  return std::visit(
      Overloaded{
          [](const Viscous& l) { return l.c; },
          [](const Coulomb& l) { return l.c; },
          [w](const Stribeck& l) {
            return l.c_b - l.w_n * l.r_m * (l.mu_s - l.mu_c) * l.gamma_b / l.nu_f * std::exp(-l.gamma_b * std::abs(w) / l.nu_f);
          },
          [w](const SqrtRegularized& l) {
            const double e2 = l.epsilon * l.epsilon;
            return l.amplitude * l.alpha * e2 / std::pow(w * w + e2, 1.5);
          },
          [w](const TanhHump& l) {
            const double th = std::tanh(w), q = 1 + l.gamma2 * w * w;
            return l.amplitude * l.beta * ((1 - th * th) + l.gamma1 * (1 - l.gamma2 * w * w) / (q * q));
          },
          [w](const Rational& l) {
            const double q = l.k * l.k * w * w + l.zeta;
            return l.p * l.k * (l.zeta - l.k * l.k * w * w) / (q * q);
          },
          [w](const Humped& l) {
            return l.t_1 * StepDerivative(l.omega_1, w) + l.t_2 * StepDerivative(l.omega_2, w) + l.b_l;
          },
          [w](const AsymmetricCoulombViscous& l) { return w >= 0 ? l.b + l.delta_b : l.b - l.delta_b; },
      },
      law_);
}

bool FrictionLaw::IsSetValued() const {
  return std::holds_alternative<Coulomb>(law_) || std::holds_alternative<Stribeck>(law_) ||
         std::holds_alternative<Humped>(law_) || std::holds_alternative<AsymmetricCoulombViscous>(law_);
}

double FrictionLaw::StaticPositive() const {
  return std::visit(Overloaded{[](const Coulomb& l) { return l.t_s; },
                               [](const Stribeck& l) { return l.w_n * l.r_m * l.mu_s; },
                               [](const Humped& l) { return l.t_sl + l.delta_t_sl; },
                               [](const AsymmetricCoulombViscous& l) { return l.t_s + l.delta_t_s; },
                               [](const auto&) { return 0.0; }},
                    law_);
}

double FrictionLaw::StaticNegative() const {
  return std::visit(Overloaded{[](const Coulomb& l) { return l.t_s; },
                               [](const Stribeck& l) { return l.w_n * l.r_m * l.mu_s; },
                               [](const Humped& l) { return l.t_sl - l.delta_t_sl; },
                               [](const AsymmetricCoulombViscous& l) { return l.t_s - l.delta_t_s; },
                               [](const auto&) { return 0.0; }},
                    law_);
}

std::string FrictionLaw::Kind() const {
  static const char* kNames[] = {"viscous", "coulomb", "stribeck", "sqrt_regularized", "tanh_hump", "rational",
                                 "humped", "asymmetric_coulomb_viscous"};
  return kNames[law_.index()];
}

FrictionLaw FrictionLaw::FromJson(const nlohmann::json& j, const std::string& json_path) {
  using io::Range;
  const io::JsonReader r(j, json_path);
  const std::string kind = r.String("law", {"viscous", "coulomb", "stribeck", "sqrt_regularized", "tanh_hump",
                                            "rational", "humped", "asymmetric_coulomb_viscous"});
  Law law = Viscous{0};
  if (kind == "viscous") {
    law = Viscous{r.Number("c_Nms_per_rad", Range::NonNegative())};
  } else if (kind == "coulomb") {
    const double tc = r.Number("T_c_Nm", Range::NonNegative());
    const double ts = r.Number("T_s_Nm", Range::AtLeast(tc), tc);
    law = Coulomb{tc, ts, r.Number("c_Nms_per_rad", Range::NonNegative(), 0.0)};
  } else if (kind == "stribeck") {
    Stribeck s{};
    s.w_n = r.Number("W_N", Range::Positive());
    s.r_m = r.Number("R_m", Range::Positive());
    s.mu_c = r.Number("mu_c", Range::NonNegative());
    s.mu_s = r.Number("mu_s", Range::AtLeast(s.mu_c));
    s.gamma_b = r.Number("gamma_b", Range::NonNegative());
    s.nu_f = r.Number("nu_f_rad_s", Range::Positive());
    s.c_b = r.Number("c_b_Nms_per_rad", Range::NonNegative());
    law = s;
  } else if (kind == "sqrt_regularized") {
    law = SqrtRegularized{r.Number("amplitude_Nm", Range::NonNegative()), r.Number("alpha", Range::NonNegative()),
                          r.Number("epsilon_rad_s", Range::Positive())};
  } else if (kind == "tanh_hump") {
    law = TanhHump{r.Number("amplitude_Nm", Range::NonNegative()), r.Number("beta", Range::NonNegative()),
                   r.Number("gamma1", Range::Any()), r.Number("gamma2", Range::NonNegative())};
  } else if (kind == "rational") {
    law = Rational{r.Number("p_Nm", Range::NonNegative()), r.Number("k", Range::Positive()),
                   r.Number("zeta", Range::Positive())};
  } else if (kind == "humped") {
    Humped h{};
    h.t_sl = r.Number("T_sl_Nm", Range::NonNegative());
    h.t_1 = r.Number("T_1_Nm", Range::Any());
    h.t_2 = r.Number("T_2_Nm", Range::Any());
    h.omega_1 = r.Number("omega_1_s_per_rad", Range::NonNegative());
    h.omega_2 = r.Number("omega_2_s_per_rad", Range::NonNegative());
    h.b_l = r.Number("b_l_Nms_per_rad", Range::NonNegative());
    h.delta_t_sl = r.Number("delta_T_sl_Nm", Range::Between(-h.t_sl, h.t_sl), 0.0);
    law = h;
  } else {
    AsymmetricCoulombViscous a{};
    a.t_s = r.Number("T_s_Nm", Range::NonNegative());
    a.delta_t_s = r.Number("delta_T_s_Nm", Range::Between(-a.t_s, a.t_s));
    a.b = r.Number("b_Nms_per_rad", Range::NonNegative());
    a.delta_b = r.Number("delta_b_Nms_per_rad", Range::Between(-a.b, a.b));
    law = a;
  }
  r.Finish();
  return FrictionLaw(law);
}

nlohmann::json FrictionLaw::ToJson() const {
  nlohmann::json j = std::visit(
      Overloaded{
          [](const Viscous& l) { return nlohmann::json{{"c_Nms_per_rad", l.c}}; },
          [](const Coulomb& l) { return nlohmann::json{{"T_c_Nm", l.t_c}, {"T_s_Nm", l.t_s}, {"c_Nms_per_rad", l.c}}; },
          [](const Stribeck& l) {
            return nlohmann::json{{"W_N", l.w_n},   {"R_m", l.r_m},         {"mu_c", l.mu_c},           {"mu_s", l.mu_s},
                                  {"gamma_b", l.gamma_b}, {"nu_f_rad_s", l.nu_f}, {"c_b_Nms_per_rad", l.c_b}};
          },
          [](const SqrtRegularized& l) {
            return nlohmann::json{{"amplitude_Nm", l.amplitude}, {"alpha", l.alpha}, {"epsilon_rad_s", l.epsilon}};
          },
          [](const TanhHump& l) {
            return nlohmann::json{{"amplitude_Nm", l.amplitude}, {"beta", l.beta}, {"gamma1", l.gamma1}, {"gamma2", l.gamma2}};
          },
          [](const Rational& l) { return nlohmann::json{{"p_Nm", l.p}, {"k", l.k}, {"zeta", l.zeta}}; },
          [](const Humped& l) {
            return nlohmann::json{{"T_sl_Nm", l.t_sl},           {"T_1_Nm", l.t_1},
                                  {"T_2_Nm", l.t_2},             {"omega_1_s_per_rad", l.omega_1},
                                  {"omega_2_s_per_rad", l.omega_2}, {"b_l_Nms_per_rad", l.b_l},
                                  {"delta_T_sl_Nm", l.delta_t_sl}};
          },
          [](const AsymmetricCoulombViscous& l) {
            return nlohmann::json{{"T_s_Nm", l.t_s}, {"delta_T_s_Nm", l.delta_t_s}, {"b_Nms_per_rad", l.b},
                                  {"delta_b_Nms_per_rad", l.delta_b}};
          },
      },
      law_);
  j["law"] = Kind();
  return j;
}

FrictionLaw FrictionLaw::Scaled(double f) const {
  if (!(f > 0)) throw std::invalid_argument("FrictionLaw::Scaled: factor must be > 0");
  return FrictionLaw(std::visit(
      Overloaded{
          [f](Viscous l) -> Law { l.c *= f; return l; },
          [f](Coulomb l) -> Law { l.t_c *= f; l.t_s *= f; l.c *= f; return l; },
          [f](Stribeck l) -> Law { l.w_n *= f; l.c_b *= f; return l; },
          [f](SqrtRegularized l) -> Law { l.amplitude *= f; return l; },
          [f](TanhHump l) -> Law { l.amplitude *= f; return l; },
          [f](Rational l) -> Law { l.p *= f; return l; },
          [f](Humped l) -> Law { l.t_sl *= f; l.t_1 *= f; l.t_2 *= f; l.b_l *= f; l.delta_t_sl *= f; return l; },
          [f](AsymmetricCoulombViscous l) -> Law { l.t_s *= f; l.delta_t_s *= f; l.b *= f; l.delta_b *= f; return l; },
      },
      law_));
}

nlohmann::json FrictionLaw::Schema() {
  return {
      {"viscous", "T = c w; c_Nms_per_rad >= 0"},
      {"coulomb", "set-valued: T = T_c sign w + c w, static T_s; T_c_Nm >= 0, T_s_Nm >= T_c (default T_c), c_Nms_per_rad >= 0 (default 0)"},
      {"stribeck", "set-valued: T = c_b w + W R (mu_c + (mu_s - mu_c) exp(-gamma_b |w| / nu_f)) sign w, static W R mu_s; W_N > 0, R_m > 0, mu_c >= 0, mu_s >= mu_c, gamma_b >= 0, nu_f_rad_s > 0, c_b_Nms_per_rad >= 0"},
      {"sqrt_regularized", "chapter eq. 2.29: T = amplitude alpha w / sqrt(w^2 + epsilon^2); amplitude_Nm >= 0, alpha >= 0, epsilon_rad_s > 0"},
      {"tanh_hump", "chapter eq. 2.30: T = amplitude beta (tanh w + gamma1 w / (1 + gamma2 w^2)); amplitude_Nm >= 0, beta >= 0, gamma1 any, gamma2 >= 0"},
      {"rational", "chapter eqs. 2.12-2.13: T = p k w / (k^2 w^2 + zeta); p_Nm >= 0, k > 0, zeta > 0"},
      {"humped", "setup seed eq. 7, set-valued: T = [T_sl + T_1 (1 - 2/(1 + e^{omega_1 |w|})) + T_2 (1 - 2/(1 + e^{omega_2 |w|})) + b_l |w|] sign w + delta_T_sl, static [-(T_sl - delta), T_sl + delta]; T_sl_Nm >= 0, T_1_Nm, T_2_Nm any, omega_1/2_s_per_rad >= 0, b_l_Nms_per_rad >= 0, delta_T_sl_Nm in [-T_sl, T_sl] (default 0)"},
      {"asymmetric_coulomb_viscous", "setup seed eqs. 5-6, set-valued: w > 0: (T_s + dT_s) + (b + db) w; w < 0: -(T_s - dT_s) + (b - db) w; T_s_Nm >= 0, delta_T_s_Nm in [-T_s, T_s], b_Nms_per_rad >= 0, delta_b_Nms_per_rad in [-b, b]"},
  };
}

}  // namespace drillwave::bitrock
