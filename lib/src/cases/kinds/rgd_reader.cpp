#include "rgd_reader.hpp"

#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "drillwave/core/error.hpp"

namespace drillwave::cases {
namespace {
// A start disturbance, not a rock property: above about a millimetre it is no longer tiny against a blade's depth of
// cut (2.6 mm at BASELINE.md's nominal point).
constexpr double kMaxRoughnessM = 1e-3;
constexpr int kDefaultRoughnessModes = 20;
// A small perturbation of the rock's strength (BASELINE.md: 0.5-1.5 %); 20 % keeps 1 + g well above zero.
constexpr double kMaxHeterogeneityStd = 0.2;
constexpr int kDefaultHeterogeneityModes = 64;

// rock/contact: the wear flats' friction function F (bitrock::ContactLaw), adimensional (amplitude 1).
bitrock::ContactLaw ReadContactLaw(const io::JsonReader& c) {
  using io::Range;
  const std::string law = c.String("law", {"set_valued", "sqrt_regularized", "tanh_hump", "tanh_hump_printed"});
  const bool squared = c.String("cutting_torque", {"rgd", "f_squared"}, "rgd") == "f_squared";
  if (law == "set_valued") {
    if (squared)
      throw InputError(c.PathOf("cutting_torque"), "expected rgd with law set_valued (eq. 2.33's F^2 needs a friction "
                                                   "function F: sqrt_regularized, tanh_hump or tanh_hump_printed)");
    c.Finish();
    return {};
  }
  std::optional<bitrock::FrictionLaw> f;
  if (law == "sqrt_regularized") {
    const double alpha = c.Number("alpha", Range::NonNegative(), 1.0);
    f.emplace(bitrock::SqrtRegularized{1.0, alpha, c.Number("epsilon_rad_s", Range::Positive())});
  } else {
    const double beta = c.Number("beta", Range::NonNegative(), 1.0), gamma1 = c.Number("gamma1", Range::NonNegative());
    const bitrock::TanhHump hump{1.0, beta, gamma1, c.Number("gamma2", Range::NonNegative())};
    if (law == "tanh_hump") f.emplace(hump);
    else f.emplace(bitrock::TanhHumpPrinted{hump});
  }
  c.Finish();
  return bitrock::ContactLaw(*f, squared ? bitrock::CuttingTorque::kFrictionSquared : bitrock::CuttingTorque::kRgd);
}
}  // namespace

void ReadRgdBit(const io::JsonReader& b, bitrock::RgdLaw& law) {
  law.a = b.Number("radius_m", io::Range::Positive());
  law.blades = b.Integer("blades", 1, 20);
}

void ReadRgdRock(const io::JsonReader& k, bitrock::RgdLaw& law) {
  using io::Range;
  law.eps = k.Number("intrinsic_specific_energy_Pa", Range::Positive());
  law.zeta = k.Number("zeta", Range::Positive());
  law.sigma_l = k.Number("sigma_l_N_per_m", Range::NonNegative());
  law.mu = k.Number("mu", Range::NonNegative());
  law.gamma = k.Number("gamma", Range::NonNegative());
  law.surface_passes = k.Integer("surface_passes", 1, 16, 4);
  if (k.Has("bottom_roughness")) {
    const io::JsonReader b = k.Object("bottom_roughness");
    const double rms = b.Number("rms_m", Range::Between(0, kMaxRoughnessM));
    const int seed = b.Integer("seed", 0, std::numeric_limits<int>::max());
    const int modes = b.Integer("modes", 1, 1000, kDefaultRoughnessModes);
    b.Finish();
    law.bottom_roughness = bitrock::BottomRoughness(rms, static_cast<std::uint64_t>(seed), modes);
  }
  if (k.Has("strength_heterogeneity")) {
    const io::JsonReader h = k.Object("strength_heterogeneity");
    const double std = h.Number("std", Range::Between(0, kMaxHeterogeneityStd));
    const double correlation = h.Number("correlation_m", Range::Between(1e-5, 1));
    const int seed = h.Integer("seed", 0, std::numeric_limits<int>::max());
    const int modes = h.Integer("modes", 1, 1000, kDefaultHeterogeneityModes);
    h.Finish();
    law.strength_heterogeneity =
        bitrock::StrengthHeterogeneity(std, correlation, static_cast<std::uint64_t>(seed), modes);
  }
  law.static_mu = law.mu;
  if (k.Has("stribeck")) {
    const io::JsonReader st = k.Object("stribeck");
    law.static_mu = st.Number("static_mu", Range::AtLeast(law.mu));
    law.stribeck_speed = st.Number("velocity_rad_s", Range::Positive());
    st.Finish();
  }
  if (k.Has("contact")) {
    law.contact_law = ReadContactLaw(k.Object("contact"));
    if (law.contact_law.has_function() && law.stribeck_speed > 0)
      throw InputError(k.PathOf("contact"), "expected either rock/stribeck or a contact law with a friction function, "
                                            "not both (F's fall with speed is its own Stribeck effect)");
  }
  k.Finish();
}

nlohmann::json RgdFieldSchema() {
  return {{"bit/radius_m", "a > 0"},
          {"bit/blades", "n, integer in [1, 20]"},
          {"rock/intrinsic_specific_energy_Pa", "eps > 0"},
          {"rock/zeta", "> 0, cutting force orientation"},
          {"rock/sigma_l_N_per_m", "sigma l >= 0, wear-flat contact strength times length"},
          {"rock/mu", ">= 0, wear-flat friction coefficient"},
          {"rock/gamma", ">= 0, friction distribution factor"},
          {"rock/surface_passes", "integer in [1, 16], default 4: the rock under a blade is the deepest position of "
                                  "the last this many blade passes (1: d = n (U(t) - U(t - t_n)) literally, against "
                                  "the previous pass even if the bit was in the air)"},
          {"rock/bottom_roughness/rms_m",
           "in [0, 0.001]: optional object (absent: a smooth bottom); the rock surface the blades left before t = 0 "
           "deviates from steady drilling's helix by h(theta) along the hole, a seeded random function of the angle "
           "around the hole with this root mean square (mean 0), so that a run from the exact steady state has a "
           "tiny disturbance to grow from (BASELINE.md's start)"},
          {"rock/bottom_roughness/seed", "integer in [0, 2147483647]: the same seed, the same surface and run"},
          {"rock/bottom_roughness/modes", "integer in [1, 1000], default 20: h = sum_{k=1..modes} of equal cosines "
                                          "cos(k theta + phi_k) with seeded random phases (shortest wavelength a "
                                          "modes-th of the circumference)"},
          {"rock/strength_heterogeneity/std",
           "in [0, 0.2]: optional object (absent: homogeneous rock); eps and sigma l are both multiplied by 1 + g(U), "
           "g a seeded, smooth, stationary random field of the drilled depth U (the bit's axial position) with mean 0 "
           "and this standard deviation (BASELINE.md's rock heterogeneity: 0.005-0.015)"},
          {"rock/strength_heterogeneity/correlation_m",
           "in [1e-5, 1] m: correlation length L, E[g(z) g(z + dz)] = std^2 exp(-(dz / L)^2 / 2) (BASELINE.md: 0.002)"},
          {"rock/strength_heterogeneity/seed", "integer in [0, 2147483647]: the same seed, the same rock and run"},
          {"rock/strength_heterogeneity/modes", "integer in [1, 1000], default 64: g = sum of this many equal cosines "
                                                "with seeded Gaussian wavenumbers (std 1 / L) and random phases"},
          {"rock/stribeck/static_mu", ">= mu: optional object (absent: Coulomb); mu(w) = mu + (static_mu - mu) "
                                      "exp(-|w| / velocity_rad_s), a stuck bit holds with static_mu"},
          {"rock/stribeck/velocity_rad_s", "> 0, Stribeck speed"},
          {"rock/contact/law",
           "set_valued | sqrt_regularized | tanh_hump | tanh_hump_printed: optional object (absent: set_valued, RGD's "
           "sign); the chapter's adimensional friction function F (eqs. 2.29-2.30) of r = |w|, the bit's angular speed "
           "in rad/s as a pure number, in T_f = a gamma mu F(|w|) W_f / 2 sign w, W_f staying RGD's axial contact; a "
           "stuck bit holds with mu F(0+), nothing for a smooth F; not with rock/stribeck"},
          {"rock/contact/alpha", ">= 0, default 1: sqrt_regularized, F(r) = alpha r / sqrt(r^2 + epsilon^2)"},
          {"rock/contact/epsilon_rad_s", "> 0: sqrt_regularized's regularization speed, F(epsilon) = alpha / sqrt(2)"},
          {"rock/contact/beta", ">= 0, default 1: tanh_hump, F(r) = beta (tanh r + gamma1 r / (1 + gamma2 r^2)); "
                                "tanh_hump_printed, F(r) = beta (tanh r + gamma1 / (1 + gamma2 r^2)), F(0+) = beta "
                                "gamma1 held at rest"},
          {"rock/contact/gamma1", ">= 0: the hump's height (s/rad in tanh_hump, a pure number in tanh_hump_printed)"},
          {"rock/contact/gamma2", ">= 0 [s^2/rad^2]: the hump's decay, its peak near r = 1 / sqrt(gamma2)"},
          {"rock/contact/cutting_torque", "rgd (default): T_c = a^2 eps d / 2 | f_squared: chapter eq. 2.33 read as "
                                          "T_c = a^2 eps d F(|w|)^2 / 2 (nothing held at rest for a smooth F)"}};
}

nlohmann::json LinearizedRock(const bitrock::RgdLaw& law) {
  if (!law.strength_heterogeneity.on()) return nullptr;
  return {{"strength_std", law.strength_heterogeneity.std()},
          {"linearized_about", "the mean rock (g = 0). The heterogeneity enters the linear system as a forcing, "
                               "eps g(V0 t) of the cutting forces, and as a modulation 1 + g of its cutting gains "
                               "along the drilled depth; neither moves the roots of its time-invariant part, which "
                               "are those of the mean rock"}};
}

}  // namespace drillwave::cases
