#pragma once
// Friction torque at a contact (bit on rock, disc on brake) as a function of its angular speed omega [rad/s].
// The torque opposes motion: it has the sign of omega and is subtracted in J omega' = T_drive - T_friction.
// Set-valued laws (Coulomb, Stribeck, humped, asymmetric) hold any torque in [-StaticNegative, StaticPositive]
// at omega = 0; the integrator treats that as a stuck regime with events (DESIGN.md §2).
//
// Each law is a plain struct of its parameters (torques in N·m, speeds in rad/s); the comment on each member
// names its key. FrictionLaw holds one of them and is an immutable value. It reads no input format: a reader hands it
// the keys it found (FrictionLaw::Read; the JSON one is cases/friction_json.hpp) and maps FrictionFieldError's key to
// its own path.
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace drillwave::bitrock {

// T = c w. Smooth; the linear reference for validation tests.
struct Viscous {
  double c;  // c_Nms_per_rad >= 0
};

// Slip T = T_c sign w + c w; stuck |T| <= T_s.
struct Coulomb {
  double t_c;  // T_c_Nm >= 0
  double t_s;  // T_s_Nm >= T_c (optional, default T_c)
  double c;    // c_Nms_per_rad >= 0 (optional, default 0)
};

// Velocity-weakening bit friction (Navarro-López; DESIGN.md §3):
// slip T = c_b w + W R mu(w) sign w with mu(w) = mu_c + (mu_s - mu_c) exp(-gamma_b |w| / nu_f); stuck |T| <= W R mu_s.
struct Stribeck {
  double weight_on_bit;  // W_N >= 0
  double bit_radius;     // R_m > 0
  double mu_c;           // mu_c >= 0, kinetic friction coefficient
  double mu_s;           // mu_s >= mu_c, static friction coefficient
  double gamma_b;        // gamma_b >= 0, decay rate of mu
  double nu_f;           // nu_f_rad_s > 0, speed scale of the decay
  double c_b;            // c_b_Nms_per_rad >= 0
};

// Chapter eq. 2.29, a smooth Coulomb law: T = p alpha w / sqrt(w^2 + epsilon^2).
struct SqrtRegularized {
  double amplitude;  // amplitude_Nm >= 0 (p)
  double alpha;      // alpha >= 0
  double epsilon;    // epsilon_rad_s > 0
};

// Chapter eq. 2.30, read as T = p beta (tanh w + gamma1 w / (1 + gamma2 w^2)), w in rad/s taken as a pure number.
// Smooth and odd; gamma1 > 0 puts a hump (velocity weakening) at about w = 1 / sqrt(gamma2).
struct TanhHump {
  double amplitude;  // amplitude_Nm >= 0 (p)
  double beta;       // beta >= 0
  double gamma1;     // gamma1 >= 0
  double gamma2;     // gamma2 >= 0
};

// Chapter eqs. 2.12-2.13: T = p k w / (k^2 w^2 + zeta). Smooth; peaks at w = sqrt(zeta) / k, then decays like 1/w.
struct Rational {
  double p;     // p_Nm >= 0
  double k;     // k > 0
  double zeta;  // zeta > 0
};

// Humped lower-disc law of the setup seed, eq. 7, with an optional asymmetry dT:
// slip T = (T_l(|w|) + dT sign w) sign w, T_l(r) = T_sl + T_1 s(omega_1 r) + T_2 s(omega_2 r) + b_l r,
// s(x) = 1 - 2 / (1 + e^x); stuck T in [-(T_sl - dT), T_sl + dT]. T_1, T_2 may be negative: that makes the hump.
struct Humped {
  double t_sl;        // T_sl_Nm >= 0
  double t_1;         // T_1_Nm, any sign
  double t_2;         // T_2_Nm, any sign
  double omega_1;     // omega_1_s_per_rad >= 0
  double omega_2;     // omega_2_s_per_rad >= 0
  double b_l;         // b_l_Nms_per_rad >= 0
  double delta_t_sl;  // delta_T_sl_Nm in [-T_sl, T_sl] (optional, default 0)
};

// Asymmetric upper-disc law of the setup seed, eqs. 5-6:
// w > 0: T = (T_s + dT_s) + (b + db) w;  w < 0: T = -(T_s - dT_s) + (b - db) w;
// stuck T in [-(T_s - dT_s), T_s + dT_s].
struct AsymmetricCoulombViscous {
  double t_s;        // T_s_Nm >= 0
  double delta_t_s;  // delta_T_s_Nm in [-T_s, T_s]
  double b;          // b_Nms_per_rad >= 0
  double delta_b;    // delta_b_Nms_per_rad in [-b, b]
};

// Chapter eq. 2.30 as printed, F(r) = beta (tanh r + gamma1 / (1 + gamma2 r^2)) of r = |w| (a norm), the torque
// opposing motion: slip T = p F(|w|) sign w; F(0) = beta gamma1 > 0, so the law jumps at rest, where it holds
// |T| <= p beta gamma1 (the limit of the slip torque). With gamma1 > 1 the torque falls from p beta gamma1 towards
// p beta: velocity weakening. The parameters (and JSON keys) of tanh_hump; gamma1 is a pure number here.
struct TanhHumpPrinted : TanhHump {};

// Chapter eq. 2.33, the cutting torque of its ref. [31], T_c = -a4 F(|w|)^2 d with F of eq. 2.29 and a depth of cut
// d held constant; the chapter's minus sign is its convention for a torque against the rotation, here the torque
// opposes motion: T = a4 d F(|w|)^2 sign w = a4 d alpha^2 w |w| / (w^2 + epsilon^2). Smooth (C1) and odd.
struct SquaredSqrtCutting {
  double a4;           // a4_N >= 0 (read as a coefficient: a^4 of the bit radius would leave units unbalanced)
  double depth;        // depth_of_cut_m >= 0 (d)
  double alpha;        // alpha >= 0
  double epsilon;      // epsilon_rad_s > 0
};

// Friction that weakens linearly with speed down to a floor, with stiction (the UFRJ rig's disc: its torque on bit
// falls almost linearly from 2.7 N m near rest to 1.0 N m at 190 rpm, where a Stribeck exponential falls too fast
// and levels off too high): slip T = max(T_0 - s |w|, T_min) sign w + c w; stuck |T| <= T_s.
struct LinearWeakening {
  double t_0;    // T_0_Nm >= 0, the slip torque as the speed leaves zero
  double t_s;    // T_s_Nm >= T_0 (optional, default T_0), the static level
  double slope;  // weakening_Nms_per_rad >= 0, the fall s per rad/s
  double t_min;  // T_min_Nm in [0, T_0] (optional, default 0), the floor the fall stops at
  double c;      // c_Nms_per_rad >= 0 (optional, default 0)
};

// A friction parameter that is missing, unknown or out of its range: the key ("law" for the kind) and what was
// expected, with the value found.
class FrictionFieldError : public std::invalid_argument {
 public:
  FrictionFieldError(std::string key, const std::string& message)
      : std::invalid_argument(message), key_(std::move(key)) {}
  const std::string& key() const { return key_; }

 private:
  std::string key_;
};

class FrictionLaw {
 public:
  using Law = std::variant<Viscous, Coulomb, Stribeck, SqrtRegularized, TanhHump, Rational, Humped,
                           AsymmetricCoulombViscous, TanhHumpPrinted, SquaredSqrtCutting, LinearWeakening>;

  // Checks the parameters against the ranges listed by Schema(); throws std::invalid_argument naming the field.
  explicit FrictionLaw(const Law& law);

  // Torque while slipping (omega != 0); smooth laws are valid at every omega. At omega == 0 exactly a set-valued
  // law returns 0, which lies in its static range; the caller decides the stuck torque, not this function.
  double SlipTorque(double omega) const;
  // d SlipTorque / d omega, for linearization. At omega == 0 a set-valued law returns the limit of the slope,
  // which is the same from both sides, except for the asymmetric law: it returns the mean b of b +- db.
  double SlipTorqueDerivative(double omega) const;
  // True for laws with a static range at omega = 0; smooth laws have StaticPositive() == StaticNegative() == 0.
  bool IsSetValued() const;
  double StaticPositive() const;  // largest torque held at rest in the positive direction (magnitude, >= 0)
  double StaticNegative() const;  // largest torque held at rest in the negative direction (magnitude, >= 0)
  const std::string& Kind() const;  // the JSON "law" name
  const Law& law() const { return law_; }

  // What a reader found under a key: nothing, a number (possibly not finite), or something else; `text` says what it
  // was for messages ("0.4", "a string \"heavy\"", "boolean true").
  struct Found {
    bool absent = true;
    std::optional<double> number;
    std::string text;
  };
  // The keys a reader was given and a look-up of each.
  struct FieldSource {
    std::vector<std::string> keys;
    std::function<Found(const std::string& key)> find;
  };
  static const std::vector<std::string>& Kinds();  // the law names, e.g. "stribeck"
  // The law `kind` from the fields a reader found. Throws FrictionFieldError naming the key for an unknown kind
  // ("law"), an unknown key, or a field that is missing, not a number, not finite or out of its range (with the value
  // found and the range expected).
  static FrictionLaw Read(const std::string& kind, const FieldSource& source);
  // Every field's key and value, defaults included: Read of these reproduces the law.
  std::vector<std::pair<std::string, double>> Values() const;

  // All torque levels (slip and static) times factor (finite, > 0), e.g. weight-on-bit scaling:
  // Scaled(f).SlipTorque(w) == f * SlipTorque(w). Throws std::invalid_argument for a bad factor.
  FrictionLaw Scaled(double factor) const;

  // Every law: its name, torque formula, static range (set-valued laws), source, and each field's key with "meaning
  // [unit]; range[; optional, default ...]", for the "drillwave kinds" listing.
  struct Description {
    std::string kind, torque, static_range, source;
    bool set_valued = false;
    std::vector<std::pair<std::string, std::string>> fields;
  };
  static std::vector<Description> Describe();

 private:
  Law law_;
};

}  // namespace drillwave::bitrock
