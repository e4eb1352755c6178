#pragma once
// Friction torque at a contact (bit on rock, disc on brake) as a function of its angular speed omega [rad/s].
// The torque opposes motion: it has the sign of omega and is subtracted in J omega' = T_drive - T_friction.
// Set-valued laws (Coulomb, Stribeck, humped, asymmetric) hold any torque in [-StaticNegative, StaticPositive]
// at omega = 0; the integrator treats that as a stuck regime with events (DESIGN.md §2).
#include <string>
#include <variant>

#include <nlohmann/json.hpp>

namespace drillwave::bitrock {

struct Viscous { double c; };                                  // T = c w
struct Coulomb { double t_c, t_s, c; };                        // T = Tc sign w + c w; static Ts
struct Stribeck { double w_n, r_m, mu_c, mu_s, gamma_b, nu_f, c_b; };  // Navarro-López & Suárez
struct SqrtRegularized { double amplitude, alpha, epsilon; };  // chapter eq. 2.29: p a w / sqrt(w^2 + e^2)
struct TanhHump { double amplitude, beta, gamma1, gamma2; };   // chapter eq. 2.30: p b (tanh w + g1 w/(1 + g2 w^2))
struct Rational { double p, k, zeta; };                        // chapter eqs. 2.12-2.13: p k w / (k^2 w^2 + zeta)
struct Humped { double t_sl, t_1, t_2, omega_1, omega_2, b_l, delta_t_sl; };  // setup seed eq. 7
struct AsymmetricCoulombViscous { double t_s, delta_t_s, b, delta_b; };     // setup seed eqs. 5-6

class FrictionLaw {
 public:
  using Law = std::variant<Viscous, Coulomb, Stribeck, SqrtRegularized, TanhHump, Rational, Humped,
                           AsymmetricCoulombViscous>;
  explicit FrictionLaw(Law law) : law_(law) {}

  // Torque while slipping (omega != 0); smooth laws are valid at every omega.
  double SlipTorque(double omega) const;
  double SlipTorqueDerivative(double omega) const;  // d SlipTorque / d omega
  bool IsSetValued() const;
  double StaticPositive() const;  // largest torque held at rest in the positive direction (magnitude)
  double StaticNegative() const;  // ... in the negative direction (magnitude)
  std::string Kind() const;       // the JSON "law" name
  const Law& law() const { return law_; }

  static FrictionLaw FromJson(const nlohmann::json& j, const std::string& json_path);
  nlohmann::json ToJson() const;
  FrictionLaw Scaled(double factor) const;  // all torque levels times factor (> 0), e.g. weight-on-bit scaling
  static nlohmann::json Schema();           // fields, units and ranges of every law

 private:
  Law law_;
};

}  // namespace drillwave::bitrock
