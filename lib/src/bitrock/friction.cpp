#include "drillwave/bitrock/friction.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <utility>

namespace drillwave::bitrock {
namespace {

using Law = FrictionLaw::Law;

// ---------------------------------------------------------------------------------------------------------------
// Field tables. Each law lists its fields once; reading, writing, validation, scaling and the schema all walk
// that list, so they cannot disagree about a key, a unit or a range.

// kWithinOther: |x| <= other; kUpToOther: 0 <= x <= other.
enum class Bound { kAny, kNonNegative, kPositive, kAtLeastOther, kWithinOther, kUpToOther };
enum class Absent { kRequired, kZero, kOther };                                   // what a missing key means

template <class L>
struct Field {
  const char* key;      // JSON key; carries the unit
  double L::*member;
  const char* meaning;  // for Describe()
  Bound bound = Bound::kAny;
  double L::*other = nullptr;  // the field a relative bound refers to; listed earlier
  bool is_torque_level = false;  // multiplied by Scaled()
  Absent absent = Absent::kRequired;
  double L::*default_from = nullptr;  // for Absent::kOther; listed earlier

  constexpr Field NonNegative() const { return With(Bound::kNonNegative, nullptr); }
  constexpr Field Positive() const { return With(Bound::kPositive, nullptr); }
  constexpr Field AtLeast(double L::*o) const { return With(Bound::kAtLeastOther, o); }
  constexpr Field Within(double L::*o) const { return With(Bound::kWithinOther, o); }
  constexpr Field UpTo(double L::*o) const { return With(Bound::kUpToOther, o); }
  constexpr Field TorqueLevel() const {
    Field f = *this;
    f.is_torque_level = true;
    return f;
  }
  constexpr Field DefaultZero() const {
    Field f = *this;
    f.absent = Absent::kZero;
    return f;
  }
  constexpr Field DefaultTo(double L::*from) const {
    Field f = *this;
    f.absent = Absent::kOther;
    f.default_from = from;
    return f;
  }

 private:
  constexpr Field With(Bound b, double L::*o) const {
    Field f = *this;
    f.bound = b;
    f.other = o;
    return f;
  }
};

// Per law: JSON name, formulas (kStatic == nullptr for smooth laws), where it comes from, and its fields.
template <class L>
struct Traits;

// Sign with sign(0) = 0, without branches.
double Sign(double w) { return static_cast<double>((w > 0) - (w < 0)); }

// ---------------------------------------------------------------------------------------------------------------
// The laws. Slip/Slope are on the integrator's hot path: no allocation, no look-ups, few branches.

template <>
struct Traits<Viscous> {
  static constexpr const char* kKind = "viscous";
  static constexpr const char* kTorque = "T = c w";
  static constexpr const char* kStatic = nullptr;
  static constexpr const char* kSource = "linear reference law for validation";
  using F = Field<Viscous>;
  static constexpr F kFields[] = {
      F{"c_Nms_per_rad", &Viscous::c, "viscous coefficient c [N·m·s/rad]"}.NonNegative().TorqueLevel(),
  };
};
double Slip(const Viscous& l, double w) { return l.c * w; }
double Slope(const Viscous& l, double) { return l.c; }

template <>
struct Traits<Coulomb> {
  static constexpr const char* kKind = "coulomb";
  static constexpr const char* kTorque = "T = T_c sign w + c w";
  static constexpr const char* kStatic = "T in [-T_s, T_s]";
  static constexpr const char* kSource = "Coulomb friction with stiction (setup seed eq. 2)";
  using F = Field<Coulomb>;
  static constexpr F kFields[] = {
      F{"T_c_Nm", &Coulomb::t_c, "sliding friction torque T_c [N·m]"}.NonNegative().TorqueLevel(),
      F{"T_s_Nm", &Coulomb::t_s, "static friction torque T_s [N·m]"}
          .AtLeast(&Coulomb::t_c).TorqueLevel().DefaultTo(&Coulomb::t_c),
      F{"c_Nms_per_rad", &Coulomb::c, "viscous coefficient c [N·m·s/rad]"}.NonNegative().TorqueLevel().DefaultZero(),
  };
};
double Slip(const Coulomb& l, double w) { return l.t_c * Sign(w) + l.c * w; }
double Slope(const Coulomb& l, double) { return l.c; }
double StaticUp(const Coulomb& l) { return l.t_s; }
double StaticDown(const Coulomb& l) { return l.t_s; }

template <>
struct Traits<Stribeck> {
  static constexpr const char* kKind = "stribeck";
  static constexpr const char* kTorque = "T = c_b w + W R (mu_c + (mu_s - mu_c) exp(-gamma_b |w| / nu_f)) sign w";
  static constexpr const char* kStatic = "T in [-W R mu_s, W R mu_s]";
  static constexpr const char* kSource =
      "Navarro-López bit friction (DESIGN.md §3): W = 97347, R = 0.155575, mu_c = 0.5, mu_s = 0.8, "
      "gamma_b = 0.9, nu_f = 1, c_b = 0.03";
  using F = Field<Stribeck>;
  static constexpr F kFields[] = {
      F{"W_N", &Stribeck::weight_on_bit, "weight on bit W [N]"}.NonNegative().TorqueLevel(),
      F{"R_m", &Stribeck::bit_radius, "bit radius R [m]"}.Positive(),
      F{"mu_c", &Stribeck::mu_c, "kinetic (Coulomb) friction coefficient [-]"}.NonNegative(),
      F{"mu_s", &Stribeck::mu_s, "static friction coefficient [-]"}.AtLeast(&Stribeck::mu_c),
      F{"gamma_b", &Stribeck::gamma_b, "decay rate of the friction coefficient [-]"}.NonNegative(),
      F{"nu_f_rad_s", &Stribeck::nu_f, "speed scale of the decay nu_f [rad/s]"}.Positive(),
      F{"c_b_Nms_per_rad", &Stribeck::c_b, "viscous coefficient at the bit c_b [N·m·s/rad]"}
          .NonNegative().TorqueLevel(),
  };
};
double StribeckDecay(const Stribeck& l, double w) { return std::exp(-l.gamma_b * std::abs(w) / l.nu_f); }
double Slip(const Stribeck& l, double w) {
  const double mu = l.mu_c + (l.mu_s - l.mu_c) * StribeckDecay(l, w);
  return l.c_b * w + l.weight_on_bit * l.bit_radius * mu * Sign(w);
}
double Slope(const Stribeck& l, double w) {  // d/dw of (mu(|w|) sign w) is mu'(|w|): the sign cancels
  return l.c_b - l.weight_on_bit * l.bit_radius * (l.mu_s - l.mu_c) * (l.gamma_b / l.nu_f) * StribeckDecay(l, w);
}
double StaticUp(const Stribeck& l) { return l.weight_on_bit * l.bit_radius * l.mu_s; }
double StaticDown(const Stribeck& l) { return StaticUp(l); }

template <>
struct Traits<SqrtRegularized> {
  static constexpr const char* kKind = "sqrt_regularized";
  static constexpr const char* kTorque = "T = p alpha w / sqrt(w^2 + epsilon^2)";
  static constexpr const char* kStatic = nullptr;
  static constexpr const char* kSource = "chapter eq. 2.29 times an amplitude p";
  using F = Field<SqrtRegularized>;
  static constexpr F kFields[] = {
      F{"amplitude_Nm", &SqrtRegularized::amplitude, "torque amplitude p [N·m]"}.NonNegative().TorqueLevel(),
      F{"alpha", &SqrtRegularized::alpha, "level alpha [-]"}.NonNegative(),
      F{"epsilon_rad_s", &SqrtRegularized::epsilon, "regularization speed epsilon [rad/s]"}.Positive(),
  };
};
double Slip(const SqrtRegularized& l, double w) {
  return l.amplitude * l.alpha * w / std::sqrt(w * w + l.epsilon * l.epsilon);
}
double Slope(const SqrtRegularized& l, double w) {
  const double e2 = l.epsilon * l.epsilon;
  const double r = 1.0 / std::sqrt(w * w + e2);
  return l.amplitude * l.alpha * e2 * r * r * r;
}

// Eq. 2.30's parameters, shared by its two readings.
template <class L>
struct TanhHumpFields {
  using F = Field<L>;
  static constexpr F kFields[] = {
      F{"amplitude_Nm", &L::amplitude, "torque amplitude p [N·m]"}.NonNegative().TorqueLevel(),
      F{"beta", &L::beta, "level beta [-]"}.NonNegative(),
      F{"gamma1", &L::gamma1, "hump height gamma1 [s/rad; a pure number in tanh_hump_printed]"}.NonNegative(),
      F{"gamma2", &L::gamma2, "hump decay gamma2 [s^2/rad^2]"}.NonNegative(),
  };
};

template <>
struct Traits<TanhHump> : TanhHumpFields<TanhHump> {
  static constexpr const char* kKind = "tanh_hump";
  static constexpr const char* kTorque = "T = p beta (tanh w + gamma1 w / (1 + gamma2 w^2)), w in rad/s as a number";
  static constexpr const char* kStatic = nullptr;
  static constexpr const char* kSource =
      "chapter eq. 2.30 times an amplitude p; the seed's layout is garbled, read with gamma1 w in the numerator "
      "so that the law is odd and smooth";
};
double Slip(const TanhHump& l, double w) {
  return l.amplitude * l.beta * (std::tanh(w) + l.gamma1 * w / (1 + l.gamma2 * w * w));
}
double Slope(const TanhHump& l, double w) {
  const double th = std::tanh(w);
  const double q = 1 + l.gamma2 * w * w;
  return l.amplitude * l.beta * ((1 - th * th) + l.gamma1 * (1 - l.gamma2 * w * w) / (q * q));
}

template <>
struct Traits<Rational> {
  static constexpr const char* kKind = "rational";
  static constexpr const char* kTorque = "T = p k w / (k^2 w^2 + zeta)";
  static constexpr const char* kStatic = nullptr;
  static constexpr const char* kSource = "chapter eqs. 2.12-2.13 (there 0 < zeta << 1, 0 < k < 1)";
  using F = Field<Rational>;
  static constexpr F kFields[] = {
      F{"p_Nm", &Rational::p, "torque amplitude p [N·m]"}.NonNegative().TorqueLevel(),
      F{"k", &Rational::k, "sharpness k [s/rad]"}.Positive(),
      F{"zeta", &Rational::zeta, "sharpness zeta [-]"}.Positive(),
  };
};
double Slip(const Rational& l, double w) { return l.p * l.k * w / (l.k * l.k * w * w + l.zeta); }
double Slope(const Rational& l, double w) {
  const double kw2 = l.k * l.k * w * w;
  const double q = kw2 + l.zeta;
  return l.p * l.k * (l.zeta - kw2) / (q * q);
}

template <>
struct Traits<Humped> {
  static constexpr const char* kKind = "humped";
  static constexpr const char* kTorque =
      "T = (T_sl + T_1 (1 - 2/(1 + e^(omega_1 |w|))) + T_2 (1 - 2/(1 + e^(omega_2 |w|))) + b_l |w| "
      "+ delta_T_sl sign w) sign w";
  static constexpr const char* kStatic = "T in [-(T_sl - delta_T_sl), T_sl + delta_T_sl]";
  static constexpr const char* kSource = "setup seed eq. 7 (lower disc); the asymmetry delta_T_sl as in eq. 5";
  using F = Field<Humped>;
  static constexpr F kFields[] = {
      F{"T_sl_Nm", &Humped::t_sl, "static friction level T_sl [N·m]"}.NonNegative().TorqueLevel(),
      F{"T_1_Nm", &Humped::t_1, "first step T_1 [N·m], negative for velocity weakening"}.TorqueLevel(),
      F{"T_2_Nm", &Humped::t_2, "second step T_2 [N·m]"}.TorqueLevel(),
      F{"omega_1_s_per_rad", &Humped::omega_1, "rate of the first step omega_1 [s/rad]"}.NonNegative(),
      F{"omega_2_s_per_rad", &Humped::omega_2, "rate of the second step omega_2 [s/rad]"}.NonNegative(),
      F{"b_l_Nms_per_rad", &Humped::b_l, "viscous coefficient b_l [N·m·s/rad]"}.NonNegative().TorqueLevel(),
      F{"delta_T_sl_Nm", &Humped::delta_t_sl, "asymmetry of the static level [N·m]"}
          .Within(&Humped::t_sl).TorqueLevel().DefaultZero(),
  };
};
// 1 - 2 / (1 + e^x) = tanh(x / 2), which does not overflow for large x.
double HumpStep(double x) { return std::tanh(0.5 * x); }
double HumpStepSlope(double x) {
  const double th = std::tanh(0.5 * x);
  return 0.5 * (1 - th * th);
}
double Slip(const Humped& l, double w) {
  const double r = std::abs(w), s = Sign(w);
  const double magnitude = l.t_sl + l.t_1 * HumpStep(l.omega_1 * r) + l.t_2 * HumpStep(l.omega_2 * r) + l.b_l * r;
  return magnitude * s + l.delta_t_sl * s * s;  // (magnitude + delta sign w) sign w
}
double Slope(const Humped& l, double w) {
  const double r = std::abs(w);
  return l.t_1 * l.omega_1 * HumpStepSlope(l.omega_1 * r) + l.t_2 * l.omega_2 * HumpStepSlope(l.omega_2 * r) + l.b_l;
}
double StaticUp(const Humped& l) { return l.t_sl + l.delta_t_sl; }
double StaticDown(const Humped& l) { return l.t_sl - l.delta_t_sl; }

template <>
struct Traits<AsymmetricCoulombViscous> {
  static constexpr const char* kKind = "asymmetric_coulomb_viscous";
  static constexpr const char* kTorque =
      "w > 0: T = (T_s + delta_T_s) + (b + delta_b) w; w < 0: T = -(T_s - delta_T_s) + (b - delta_b) w";
  static constexpr const char* kStatic = "T in [-(T_s - delta_T_s), T_s + delta_T_s]";
  static constexpr const char* kSource =
      "setup seed eqs. 5-6 (upper disc): T_s = 0.3212, delta_T_s = 0.0095, b = 1.9833, delta_b = 0.0167";
  using F = Field<AsymmetricCoulombViscous>;
  static constexpr F kFields[] = {
      F{"T_s_Nm", &AsymmetricCoulombViscous::t_s, "mean static friction level T_s [N·m]"}.NonNegative().TorqueLevel(),
      F{"delta_T_s_Nm", &AsymmetricCoulombViscous::delta_t_s, "asymmetry of the static level [N·m]"}
          .Within(&AsymmetricCoulombViscous::t_s).TorqueLevel(),
      F{"b_Nms_per_rad", &AsymmetricCoulombViscous::b, "mean viscous coefficient b [N·m·s/rad]"}
          .NonNegative().TorqueLevel(),
      F{"delta_b_Nms_per_rad", &AsymmetricCoulombViscous::delta_b, "asymmetry of the viscous coefficient [N·m·s/rad]"}
          .Within(&AsymmetricCoulombViscous::b).TorqueLevel(),
  };
};
double Slip(const AsymmetricCoulombViscous& l, double w) {
  const double s = Sign(w);
  return l.t_s * s + l.delta_t_s * s * s + (l.b + l.delta_b * s) * w;
}
double Slope(const AsymmetricCoulombViscous& l, double w) { return l.b + l.delta_b * Sign(w); }
double StaticUp(const AsymmetricCoulombViscous& l) { return l.t_s + l.delta_t_s; }
double StaticDown(const AsymmetricCoulombViscous& l) { return l.t_s - l.delta_t_s; }

template <>
struct Traits<TanhHumpPrinted> : TanhHumpFields<TanhHumpPrinted> {
  static constexpr const char* kKind = "tanh_hump_printed";
  static constexpr const char* kTorque = "T = p beta (tanh |w| + gamma1 / (1 + gamma2 w^2)) sign w, w in rad/s as a number";
  static constexpr const char* kStatic = "T in [-p beta gamma1, p beta gamma1]";
  static constexpr const char* kSource = "chapter eq. 2.30 as printed, times an amplitude p (compare tanh_hump)";
};
double Slip(const TanhHumpPrinted& l, double w) {
  return l.amplitude * l.beta * (std::tanh(std::abs(w)) + l.gamma1 / (1 + l.gamma2 * w * w)) * Sign(w);
}
double Slope(const TanhHumpPrinted& l, double w) {  // d/dw of F(|w|) sign w is F'(|w|)
  const double th = std::tanh(std::abs(w));
  const double q = 1 + l.gamma2 * w * w;
  return l.amplitude * l.beta * ((1 - th * th) - 2 * l.gamma1 * l.gamma2 * std::abs(w) / (q * q));
}
double StaticUp(const TanhHumpPrinted& l) { return l.amplitude * l.beta * l.gamma1; }
double StaticDown(const TanhHumpPrinted& l) { return StaticUp(l); }

template <>
struct Traits<SquaredSqrtCutting> {
  static constexpr const char* kKind = "squared_sqrt_cutting";
  static constexpr const char* kTorque = "T = a4 d F(|w|)^2 sign w, F(r) = alpha r / sqrt(r^2 + epsilon^2)";
  static constexpr const char* kStatic = nullptr;
  static constexpr const char* kSource =
      "chapter eq. 2.33 (its ref. [31]) with F of eq. 2.29 and a constant depth of cut d; the chapter's minus sign is "
      "its convention for a torque against the rotation";
  using F = Field<SquaredSqrtCutting>;
  static constexpr F kFields[] = {
      F{"a4_N", &SquaredSqrtCutting::a4, "cutting coefficient a4 [N] (torque per depth of cut)"}
          .NonNegative().TorqueLevel(),
      F{"depth_of_cut_m", &SquaredSqrtCutting::depth, "depth of cut d [m]"}.NonNegative(),
      F{"alpha", &SquaredSqrtCutting::alpha, "level alpha of F [-]"}.NonNegative(),
      F{"epsilon_rad_s", &SquaredSqrtCutting::epsilon, "regularization speed epsilon of F [rad/s]"}.Positive(),
  };
};
// F(|w|)^2 sign w = F(w) |F(w)| with F of eq. 2.29 (odd), whose slope is 2 |F| F'.
SqrtRegularized CuttingFunction(const SquaredSqrtCutting& l) { return {1.0, l.alpha, l.epsilon}; }
double Slip(const SquaredSqrtCutting& l, double w) {
  const double f = Slip(CuttingFunction(l), w);
  return l.a4 * l.depth * f * std::abs(f);
}
double Slope(const SquaredSqrtCutting& l, double w) {
  return l.a4 * l.depth * 2 * std::abs(Slip(CuttingFunction(l), w)) * Slope(CuttingFunction(l), w);
}

template <>
struct Traits<LinearWeakening> {
  static constexpr const char* kKind = "linear_weakening";
  static constexpr const char* kTorque = "T = max(T_0 - s |w|, T_min) sign w + c w";
  static constexpr const char* kStatic = "T in [-T_s, T_s]";
  static constexpr const char* kSource =
      "the UFRJ rig's torque on bit against its disc's speed, binned (falls almost linearly, issue 32)";
  using F = Field<LinearWeakening>;
  static constexpr F kFields[] = {
      F{"T_0_Nm", &LinearWeakening::t_0, "slip torque as the speed leaves zero T_0 [N·m]"}.NonNegative().TorqueLevel(),
      F{"T_s_Nm", &LinearWeakening::t_s, "static friction torque T_s [N·m]"}
          .AtLeast(&LinearWeakening::t_0).TorqueLevel().DefaultTo(&LinearWeakening::t_0),
      F{"weakening_Nms_per_rad", &LinearWeakening::slope, "fall of the slip torque per speed s [N·m·s/rad]"}
          .NonNegative().TorqueLevel(),
      F{"T_min_Nm", &LinearWeakening::t_min, "floor of the fall T_min [N·m]"}
          .UpTo(&LinearWeakening::t_0).TorqueLevel().DefaultZero(),
      F{"c_Nms_per_rad", &LinearWeakening::c, "viscous coefficient c [N·m·s/rad]"}
          .NonNegative().TorqueLevel().DefaultZero(),
  };
};
double Slip(const LinearWeakening& l, double w) {
  return std::max(l.t_0 - l.slope * std::abs(w), l.t_min) * Sign(w) + l.c * w;
}
double Slope(const LinearWeakening& l, double w) {  // d/dw of F(|w|) sign w is F'(|w|)
  return (l.t_0 - l.slope * std::abs(w) > l.t_min ? -l.slope : 0.0) + l.c;
}
double StaticUp(const LinearWeakening& l) { return l.t_s; }
double StaticDown(const LinearWeakening& l) { return l.t_s; }

template <class L>
constexpr bool IsSetValuedLaw() {
  return Traits<L>::kStatic != nullptr;
}

// Smooth laws hold no torque at rest; every set-valued law has its own overloads above.
template <class L>
double StaticUp(const L&) {
  static_assert(!IsSetValuedLaw<L>(), "a set-valued law needs StaticUp and StaticDown");
  return 0.0;
}
template <class L>
double StaticDown(const L&) {
  static_assert(!IsSetValuedLaw<L>(), "a set-valued law needs StaticUp and StaticDown");
  return 0.0;
}

// ---------------------------------------------------------------------------------------------------------------
// Generic machinery over the field tables.

template <class L>
using TraitsOf = Traits<std::decay_t<L>>;

constexpr std::size_t kNumLaws = std::variant_size_v<Law>;

template <std::size_t... I>
std::array<std::string, kNumLaws> KindNames(std::index_sequence<I...>) {
  return {Traits<std::variant_alternative_t<I, Law>>::kKind...};
}

const std::array<std::string, kNumLaws>& Kinds() {
  static const std::array<std::string, kNumLaws> kinds = KindNames(std::make_index_sequence<kNumLaws>());
  return kinds;
}

std::string KindList() {
  std::string list;
  for (const std::string& k : Kinds()) list += (list.empty() ? "" : ", ") + k;
  return list;
}

std::string Format(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", x);
  return text;
}

template <class L>
std::string KeyOf(double L::*member) {
  for (const auto& f : Traits<L>::kFields)
    if (f.member == member) return f.key;
  return "?";
}

template <class L>
std::string RangeText(const Field<L>& f) {
  switch (f.bound) {
    case Bound::kAny: return "a finite number";
    case Bound::kNonNegative: return "a number >= 0";
    case Bound::kPositive: return "a number > 0";
    case Bound::kAtLeastOther: return "a number >= " + KeyOf(f.other);
    case Bound::kWithinOther: return "a number in [-" + KeyOf(f.other) + ", " + KeyOf(f.other) + "]";
    case Bound::kUpToOther: return "a number in [0, " + KeyOf(f.other) + "]";
  }
  return "";
}

// For error messages: the range with the value of the field it refers to, e.g. "a number >= mu_c (mu_c = 0.5)".
template <class L>
std::string RangeText(const Field<L>& f, const L& law) {
  if (f.other == nullptr) return RangeText(f);
  return RangeText(f) + " (" + KeyOf(f.other) + " = " + Format(law.*f.other) + ")";
}

template <class L>
bool InRange(const Field<L>& f, const L& law) {
  const double x = law.*f.member;
  if (!std::isfinite(x)) return false;
  switch (f.bound) {
    case Bound::kAny: return true;
    case Bound::kNonNegative: return x >= 0;
    case Bound::kPositive: return x > 0;
    case Bound::kAtLeastOther: return x >= law.*f.other;
    case Bound::kWithinOther: return std::abs(x) <= law.*f.other;
    case Bound::kUpToOther: return x >= 0 && x <= law.*f.other;
  }
  return false;
}

template <class L>
bool HasField(const std::string& key) {
  for (const auto& f : Traits<L>::kFields)
    if (key == f.key) return true;
  return false;
}

template <class L>
L ReadLaw(const FrictionLaw::FieldSource& source) {
  // Unknown keys first: a misspelt key would otherwise be reported as a missing one.
  for (const std::string& key : source.keys) {
    if (key == "law" || HasField<L>(key)) continue;
    std::string known = "law";
    for (const auto& f : Traits<L>::kFields) known += std::string(", ") + f.key;
    throw FrictionFieldError(key, std::string("unknown field of friction law \"") + Traits<L>::kKind +
                                      "\"; expected one of: " + known);
  }
  L law{};
  for (const auto& f : Traits<L>::kFields) {
    const FrictionLaw::Found found = source.find(f.key);
    if (found.absent) {
      if (f.absent == Absent::kRequired) throw FrictionFieldError(f.key, "missing required field (" + RangeText(f) + ")");
      law.*f.member = f.absent == Absent::kOther ? law.*f.default_from : 0.0;
      continue;
    }
    if (!found.number) throw FrictionFieldError(f.key, "expected " + RangeText(f, law) + ", got " + found.text);
    law.*f.member = *found.number;
    if (!std::isfinite(law.*f.member))
      throw FrictionFieldError(f.key, "expected a finite number (" + RangeText(f, law) + "), got " + found.text);
    if (!InRange(f, law)) throw FrictionFieldError(f.key, "expected " + RangeText(f, law) + ", got " + found.text);
  }
  return law;
}

template <std::size_t... I>
std::optional<Law> ReadKind(const std::string& kind, const FrictionLaw::FieldSource& source,
                            std::index_sequence<I...>) {
  std::optional<Law> law;
  (void)((kind == Traits<std::variant_alternative_t<I, Law>>::kKind
              ? (law = ReadLaw<std::variant_alternative_t<I, Law>>(source), true)
              : false) ||
         ...);
  return law;
}

template <class L>
FrictionLaw::Description DescriptionOf() {
  FrictionLaw::Description d;
  d.kind = Traits<L>::kKind;
  d.torque = Traits<L>::kTorque;
  d.source = Traits<L>::kSource;
  d.set_valued = IsSetValuedLaw<L>();
  if (d.set_valued) d.static_range = Traits<L>::kStatic;
  for (const auto& f : Traits<L>::kFields) {
    std::string text = std::string(f.meaning) + "; " + RangeText(f);
    if (f.absent == Absent::kZero) text += "; optional, default 0";
    if (f.absent == Absent::kOther) text += "; optional, default " + KeyOf(f.default_from);
    d.fields.emplace_back(f.key, text);
  }
  return d;
}

template <std::size_t... I>
std::vector<FrictionLaw::Description> DescriptionsOfAll(std::index_sequence<I...>) {
  return {DescriptionOf<std::variant_alternative_t<I, Law>>()...};
}

}  // namespace

FrictionLaw::FrictionLaw(const Law& law) : law_(law) {
  std::visit(
      [](const auto& l) {
        using Tr = TraitsOf<decltype(l)>;
        for (const auto& f : Tr::kFields) {
          if (InRange(f, l)) continue;
          throw std::invalid_argument(std::string("friction law \"") + Tr::kKind + "\": " + f.key + ": expected " +
                                      RangeText(f, l) + ", got " + Format(l.*f.member));
        }
      },
      law_);
}

double FrictionLaw::SlipTorque(double omega) const {
  return std::visit([omega](const auto& l) { return Slip(l, omega); }, law_);
}

double FrictionLaw::SlipTorqueDerivative(double omega) const {
  return std::visit([omega](const auto& l) { return Slope(l, omega); }, law_);
}

bool FrictionLaw::IsSetValued() const {
  return std::visit([](const auto& l) { return IsSetValuedLaw<std::decay_t<decltype(l)>>(); }, law_);
}

double FrictionLaw::StaticPositive() const {
  return std::visit([](const auto& l) { return StaticUp(l); }, law_);
}

double FrictionLaw::StaticNegative() const {
  return std::visit([](const auto& l) { return StaticDown(l); }, law_);
}

const std::string& FrictionLaw::Kind() const { return Kinds()[law_.index()]; }

const std::vector<std::string>& FrictionLaw::Kinds() {
  static const std::vector<std::string> kinds(bitrock::Kinds().begin(), bitrock::Kinds().end());
  return kinds;
}

FrictionLaw FrictionLaw::Read(const std::string& kind, const FieldSource& source) {
  const std::optional<Law> law = ReadKind(kind, source, std::make_index_sequence<kNumLaws>());
  if (!law) throw FrictionFieldError("law", "expected one of: " + KindList() + ", got a string \"" + kind + "\"");
  return FrictionLaw(*law);
}

std::vector<std::pair<std::string, double>> FrictionLaw::Values() const {
  std::vector<std::pair<std::string, double>> values;
  std::visit(
      [&values](const auto& l) {
        for (const auto& f : TraitsOf<decltype(l)>::kFields) values.emplace_back(f.key, l.*f.member);
      },
      law_);
  return values;
}

FrictionLaw FrictionLaw::Scaled(double factor) const {
  if (!(factor > 0 && std::isfinite(factor)))
    throw std::invalid_argument("FrictionLaw::Scaled: expected a finite factor > 0, got " + Format(factor));
  return FrictionLaw(std::visit(
      [factor](auto l) -> Law {
        for (const auto& f : TraitsOf<decltype(l)>::kFields)
          if (f.is_torque_level) l.*f.member *= factor;
        return l;
      },
      law_));
}

std::vector<FrictionLaw::Description> FrictionLaw::Describe() {
  return DescriptionsOfAll(std::make_index_sequence<kNumLaws>());
}

}  // namespace drillwave::bitrock
