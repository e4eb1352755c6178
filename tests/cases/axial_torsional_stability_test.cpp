// Linearized stability of the coupled axial-torsional kind (RGD bit-rock law with the cut delay t_n) against a
// characteristic function written by hand and against simulation of the kind itself.
//
// Closed form (no distributed damping): the internal nodes of each channel then pass every wave on unchanged, so each
// channel is one uniform section of impedance Z and travel time tau. Seen from the bit it pulls with -Z g(s) v_b,
//   g(s) = (1 - R e^{-2 s tau}) / (1 + R e^{-2 s tau}),  R = (Z - Y_top) / (Z + Y_top)
// (Aarsnes & Aamo 2016's g with R in place of -eta), Y_top = J s + kp + ki / s for the PI top drive and M_h s for the
// hoist under a constant hook force. A top-drive law (model::TopDriveLaw) makes the top's (J s + C L) / (1 + g C H L):
// the PI's C = kp + ki / s behind the actuator delay L = e^{-s d}, tracking the set-point less g times the string
// torque high-passed by H = s tau_f / (1 + s tau_f). With D_t = J_b s + Z_t g_t, D_a = M_b s + Z_a g_a,
// E = n (1 - e^{-s t_n0}) / s and delta d = E (v_b - (V0 / Omega0) w_b), the bit's two equations
// D_t w_b + (a^2 eps / 2) delta d = 0 and D_a v_b + a zeta eps delta d = 0 have the determinant
//   F(s) = D_t D_a + E (a zeta eps D_t - (a^2 eps / 2) (V0 / Omega0) D_a),
// whose zeros must be the spectrum's roots.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <string>
#include <vector>

#include "complex_newton.hpp"
#include "drillwave/analysis/induction_linearization.hpp"
#include "drillwave/analysis/spectrum.hpp"
#include "drillwave/cases/case_runner.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/io/json_reader.hpp"
#include "drillwave/model/hoist_rig.hpp"
#include "drillwave/model/induction_motor.hpp"
#include "json_case.hpp"
#include "wave_cancelling_top.hpp"

namespace drillwave::cases {
namespace {

using Complex = std::complex<double>;

nlohmann::json Baseline() {
  return testing::LoadCase("baseline-60rpm");
}

std::vector<LinearizedOperatingPoint> Linearize(const nlohmann::json& doc) { return ParseCase(doc).model->Linearize(); }

// The baseline's string and bit without distributed damping or mud, in `pieces` sub-sections.
nlohmann::json Undamped(int pieces) {
  nlohmann::json doc = Baseline();
  auto& s = doc["model"]["string"];
  s["torsional_damping_Nms_per_rad_m"] = 0;
  s["axial_damping_Ns_per_m2"] = 0;
  s["subsections"] = pieces;
  doc["model"]["top"]["speed_rad_s"] = 2 * kPi;
  return doc;
}

struct ClosedForm {
  double zt, taut, za, taua, j_top, kp, ki, j_bit, m_hoist, m_bit, cut_w, cut_t, blades, tn0, ratio;
  double gear_ratio = 1, gear_k = 0, gear_c = 0, j_motor = 0, dc_k = 0, dc_r = 0, dc_l = 0;  // optional top parts
  double rig_m1 = 0, rig_m2 = 0, rig_g1 = 0, rig_g2 = 0, rig_k01 = 0, rig_k12 = 0;            // optional hoisting rig
  double hoist_c = 0;                                                                          // optional hoist dashpot
  // The rig's optional drawworks: drum inertia, line radius, gear ratio and its motor's linear torque per drum speed
  // n^2 G(s), G = dT/dpsi (s I - dF/dpsi)^-1 dF/dw_m at the steady supply (analysis::LinearizeInductionMotor).
  double drum_j = 0, drum_r = 0, drum_n = 1;
  analysis::InductionJacobian drum_motor;
  double feedback_gain = 0, feedback_tau = 0, delay = 0;                                       // optional top-drive law
  double wave_corner = 0;                                                              // the wave cancellation's k
  int pieces = 1;
  double kv_t = 0, kv_a = 0;  // optional Kelvin-Voigt dashpots eta K / piece length across each piece
  explicit ClosedForm(const nlohmann::json& doc) {
    const auto& m = doc["model"];
    const auto& s = m["string"];
    const double od = s["outer_diameter_m"], id = s["inner_diameter_m"], length = s["length_m"];
    const double g = s["shear_modulus_Pa"], e = s["youngs_modulus_Pa"], rho = s["density_kg_m3"];
    const double polar = kPi / 32 * (std::pow(od, 4) - std::pow(id, 4)), area = kPi / 4 * (od * od - id * id);
    zt = polar * std::sqrt(g * rho), taut = length / std::sqrt(g / rho);
    za = area * std::sqrt(e * rho), taua = length / std::sqrt(e / rho);
    pieces = s.value("subsections", 20);
    kv_t = s.value("kelvin_voigt_s", 0.0) * g * polar / (length / pieces);
    kv_a = s.value("axial_kelvin_voigt_s", 0.0) * e * area / (length / pieces);
    j_top = m["top"]["inertia_kgm2"], kp = m["top"]["kp_Nms_per_rad"], ki = m["top"].value("ki_Nm_per_rad", 0.0);
    j_bit = m["bit"]["inertia_kgm2"], m_bit = m["bit"]["mass_kg"], m_hoist = m["hoist"]["mass_kg"];
    hoist_c = m["hoist"].value("damping_Ns_per_m", 0.0);
    const double a = m["bit"]["radius_m"], eps = m["rock"]["intrinsic_specific_energy_Pa"], zeta = m["rock"]["zeta"];
    const double sigma_l = m["rock"]["sigma_l_N_per_m"], w0 = m["top"]["speed_rad_s"], wob = m["hoist"]["weight_on_bit_N"];
    blades = m["bit"]["blades"];
    cut_w = a * zeta * eps, cut_t = 0.5 * a * a * eps;
    tn0 = 2 * kPi / (blades * w0);
    const double depth = (wob - a * sigma_l) / cut_w;  // per revolution
    ratio = depth / (2 * kPi);                       // V0 / Omega0
    const auto& top = m["top"];
    if (top.contains("gear")) {
      gear_ratio = top["gear"]["ratio"], j_motor = top["motor_inertia_kgm2"];
      gear_k = top["gear"].value("stiffness_Nm_per_rad", 0.0), gear_c = top["gear"].value("damping_Nms_per_rad", 0.0);
    }
    if (m["hoist"].contains("rig")) {
      const auto& r = m["hoist"]["rig"];
      rig_m1 = r["derrick_mass_kg"], rig_m2 = r["block_mass_kg"];
      rig_g1 = r["derrick_damping_Ns_per_m"], rig_g2 = r["block_damping_Ns_per_m"];
      rig_k01 = r["ground_stiffness_N_per_m"], rig_k12 = r["cable_stiffness_N_per_m"];
      if (r.contains("drawworks")) {  // at the supply that pays out the steady rate of penetration (the run's summary)
        const auto& d = r["drawworks"];
        drum_j = d["inertia_kgm2"], drum_r = d["line_radius_m"], drum_n = d.value("gear_ratio", 1.0);
        nlohmann::json start = doc;
        start["simulation"]["duration_s"] = 0.01;
        start.erase("statistics"), start.erase("expect");
        const double f0 = RunCase(ParseCase(start)).summary["drawworks_steady_supply_frequency_Hz"];
        const auto& im = d["induction_motor"];
        model::InductionMotor motor;
        motor.pole_pairs = im["pole_pairs"];
        motor.stator_resistance = im["stator_resistance_ohm"], motor.rotor_resistance = im["rotor_resistance_ohm"];
        motor.stator_leakage_inductance = im["stator_leakage_inductance_H"];
        motor.rotor_leakage_inductance = im["rotor_leakage_inductance_H"];
        motor.magnetizing_inductance = im["magnetizing_inductance_H"];
        motor.volts_per_hertz = im["volts_per_hertz_V_per_Hz"], motor.voltage_limit = im.value("voltage_limit_V", 0.0);
        drum_motor = analysis::LinearizeInductionMotor(motor, f0, drum_n * ratio * w0 / drum_r);
      }
    }
    const std::string type = top.value("type", std::string("top_drive"));
    if (type == "soft_torque") feedback_gain = top.value("feedback_gain_rad_per_Nms", 0.0);
    if (type == "z_torque") feedback_gain = 1 / top.value("impedance_Nms_per_rad", zt);
    if (type == "wave_cancellation") wave_corner = top["speed_loop_corner_rad_s"], ki = 2 * zt * wave_corner;
    feedback_tau = top.value("feedback_time_constant_s", 0.0), delay = top.value("actuator_delay_s", 0.0);
    if (top.contains("motor")) {
      dc_k = gear_ratio * top["motor"]["motor_constant_Nm_per_A"].get<double>();
      dc_r = top["motor"]["resistance_ohm"], dc_l = top["motor"]["inductance_H"];
    }
  }
  // The top's impedance. The PI's torque kp + ki / s, or through a DC motor (K referred to the top drive, voltage
  // R / K u_PI + K Omega_ref, (L s + R) I = V - K w) the torque K I = (R (kp + ki / s) + K^2) / (L s + R) per speed.
  // A rigid gear adds n^2 J_m to J; behind a compliant one the motor side M = n^2 J_m s + drive is in series with the
  // gear's k / s + c.
  Complex TopImpedance(Complex s) const {
    if (wave_corner > 0) {  // tests/support/wave_cancelling_top.hpp, the undamped top node
      const testing::WaveCancellingTop top{j_top + gear_ratio * gear_ratio * j_motor, kp, wave_corner, 0, delay};
      const auto [num, den] = top.Impedance(zt, s);
      return num / den;
    }
    const Complex drive = dc_k > 0 ? (dc_r * (kp + ki / s) + dc_k * dc_k) / (dc_l * s + dc_r) : kp + ki / s;
    const double j_referred = gear_ratio * gear_ratio * j_motor;
    if (feedback_gain > 0 || delay > 0) {  // a law: rigid gear, no motor
      const Complex late = drive * std::exp(-s * delay), high_pass = s * feedback_tau / (1.0 + s * feedback_tau);
      return ((j_top + j_referred) * s + late) / (1.0 + feedback_gain * late * high_pass);
    }
    if (gear_k == 0) return (j_top + j_referred) * s + drive;
    const Complex motor = j_referred * s + drive, gear = gear_k / s + gear_c;
    return j_top * s + gear * motor / (gear + motor);
  }
  // The hoist's impedance: M_h s under a constant hook force, M_h s + c_h with its dashpot. Hanging from the rig
  // (chapter eq. 2.22) it carries the block, (M_h + M2) s + gamma2, and the cable k12 delta with delta = (v - s y1) / s
  // and (M1 s^2 + gamma1 s + k01) y1 = k12 delta: k12 D1 / (s (D1 + k12)), D1 = M1 s^2 + gamma1 s + k01. With a
  // drawworks the line's lower end moves by r w_d too, delta = (v - s y1 - r w_d) / s, and the drum turns under the
  // line's pull P = gamma2 v + k12 delta and its motor: (J s - n^2 G) w_d = r P. With Q = r^2 / (J s - n^2 G) the
  // cable's force F = k12 delta = v (1 - Q gamma2) / (s / k12 + s / D1 + Q) (Q = 0: the constant pay-out's).
  Complex HoistImpedance(Complex s) const {
    if (rig_m1 == 0) return m_hoist * s + hoist_c;
    const Complex d1 = rig_m1 * s * s + rig_g1 * s + rig_k01;
    if (drum_j == 0) return (m_hoist + rig_m2) * s + rig_g2 + rig_k12 * d1 / (s * (d1 + rig_k12));
    const Eigen::Matrix4cd resolvent = (s * Eigen::Matrix4cd::Identity() - drum_motor.flux.cast<Complex>()).inverse();
    const Complex g = (drum_motor.torque.cast<Complex>() * resolvent * drum_motor.shaft_speed.cast<Complex>())(0, 0);
    const Complex q = drum_r * drum_r / (drum_j * s - drum_n * drum_n * g);
    return (m_hoist + rig_m2) * s + rig_g2 + (1.0 - q * rig_g2) / (s / rig_k12 + s / d1 + q);
  }
  static Complex G(Complex s, double z, Complex y, double tau) {
    const Complex r = (z - y) / (z + y), e = r * std::exp(-2.0 * s * tau);
    return (1.0 - e) / (1.0 + e);
  }
  // The impedance seen from the bit into a channel of `pieces` pieces (impedance z, travel time tau / pieces each)
  // with a dashpot c across each, ending in the load y at the top. A piece with its dashpot is the two-port
  // T1 = A w1 - B w2, T2 = -B w1 + A w2 with A = z coth(s tau_p) + c, B = z csch(s tau_p) + c, so a load y on its
  // upper port is seen from its lower port as A - B^2 / (A + y), piece by piece from the top down. With c = 0 this
  // is z g(s).
  Complex DampedChannel(Complex s, double z, Complex y, double tau, double c) const {
    const Complex e = std::exp(-s * tau / double(pieces)), q = e * e;
    const Complex a = z * (1.0 + q) / (1.0 - q) + c, b = z * 2.0 * e / (1.0 - q) + c;
    for (int k = 0; k < pieces; ++k) y = a - b * b / (a + y);
    return y;
  }
  Complex operator()(Complex s) const {
    const Complex dt = j_bit * s + (kv_t > 0 ? DampedChannel(s, zt, TopImpedance(s), taut, kv_t)
                                             : zt * G(s, zt, TopImpedance(s), taut));
    const Complex da = m_bit * s + (kv_a > 0 ? DampedChannel(s, za, HoistImpedance(s), taua, kv_a)
                                             : za * G(s, za, HoistImpedance(s), taua));
    const Complex e = blades * (1.0 - std::exp(-s * tn0)) / s;
    return dt * da + e * (cut_w * dt - cut_t * ratio * da);
  }
  bool Refine(Complex& s) const { return testing::NewtonZero(*this, s); }
};

// Every root of the linearization with |Im s| <= 40 is a zero of F to 1e-10 (Newton on F from it moves it by less), and
// every zero of F found by Newton from a grid of starts in Re s in [-4, 4], Im s in [0, 40] is among the roots.
void ExpectRootsAreTheZerosOfTheClosedForm(const nlohmann::json& doc, const std::string& what) {
  const auto points = Linearize(doc);
  ASSERT_EQ(points.size(), 1u) << what;
  analysis::SpectrumOptions o;
  o.im_max = 60;
  const analysis::Spectrum sp = analysis::ComputeSpectrum(points[0].system, o);
  const ClosedForm f(doc);
  int checked = 0;
  double worst = 0;
  for (const auto& r : sp.roots) {
    if (r.s.imag() > 40 || r.s.real() < -4) continue;
    Complex s = r.s;
    ASSERT_TRUE(f.Refine(s)) << what << ": " << r.s;
    worst = std::max(worst, std::abs(s - r.s) / (1 + std::abs(r.s)));
    EXPECT_LT(std::abs(s - r.s), 1e-10 * (1 + std::abs(r.s))) << what << ": root " << r.s;
    ++checked;
  }
  std::vector<Complex> zeros;
  for (double re = -4; re <= 4; re += 1)
    for (double im = 0.25; im <= 40; im += 0.5) {
      Complex s(re, im);
      if (!f.Refine(s) || s.real() < -3.9 || s.real() > 4 || std::abs(s.imag()) > 39 || std::abs(s) < 1e-6) continue;
      if (s.imag() < 0) s = std::conj(s);
      bool found = false;
      for (const auto& r : sp.roots) found |= std::abs(r.s - s) < 1e-9 * (1 + std::abs(s));
      EXPECT_TRUE(found) << what << ": zero " << s << " of the closed form is not among the roots";
      bool seen = false;
      for (const Complex& z : zeros) seen |= std::abs(z - s) < 1e-9 * (1 + std::abs(s));
      if (!seen) zeros.push_back(s);
    }
  std::printf("[ measured ] %s: %d roots with Im s <= 40 are zeros of F (largest relative Newton correction %.2e), %d "
              "distinct Newton zeros of F (Re s in [-4, 4], Im s <= 39) all among them; rightmost %.10f%+.10fi, "
              "essential %.3e (%s)\n", what.c_str(), checked, worst, static_cast<int>(zeros.size()),
              sp.roots[0].s.real(), sp.roots[0].s.imag(), sp.essential_abscissa, analysis::VerdictName(sp.verdict));
  EXPECT_GE(checked, 10) << what;
}

TEST(AxialTorsionalStability, RootsAreTheZerosOfTheClosedFormOfTheUndampedString) {
  for (int pieces : {2, 5})
    ExpectRootsAreTheZerosOfTheClosedForm(Undamped(pieces), "undamped baseline string in " + std::to_string(pieces) +
                                                                " pieces");
}

// The top drive's motor and gear: the rig's compliant 8:1 gear with the motor's inertia behind it (the PI on the motor
// speed), and a DC motor through a rigid gear with its inertia.
// Kelvin-Voigt dashpots across the pieces of both channels (the retardation times of
// json-cases/baseline-kelvin-voigt.json and a tenth of it axially): the channels are no longer single sections, and
// the closed form chains the pieces' two-ports.
TEST(AxialTorsionalStability, KelvinVoigtRootsAreTheZerosOfTheChainedClosedForm) {
  for (int pieces : {2, 5}) {
    nlohmann::json doc = Undamped(pieces);
    doc["model"]["string"]["kelvin_voigt_s"] = 0.024;
    doc["model"]["string"]["axial_kelvin_voigt_s"] = 0.0024;
    ExpectRootsAreTheZerosOfTheClosedForm(doc, "Kelvin-Voigt string in " + std::to_string(pieces) + " pieces");
  }
}

TEST(AxialTorsionalStability, GearedAndMotorTopsAreTheZerosOfTheClosedForm) {
  nlohmann::json compliant = Undamped(2);
  compliant["model"]["top"]["gear"] = {{"ratio", 8}, {"stiffness_Nm_per_rad", 3e5}, {"damping_Nms_per_rad", 20}};
  compliant["model"]["top"]["motor_inertia_kgm2"] = 10;
  ExpectRootsAreTheZerosOfTheClosedForm(compliant, "undamped string in 2 pieces, compliant gear");
  nlohmann::json dc = Undamped(2);
  dc["model"]["top"]["motor"] = {{"motor_constant_Nm_per_A", 10}, {"resistance_ohm", 0.01}, {"inductance_H", 1e-3}};
  dc["model"]["top"]["gear"] = {{"ratio", 8}};
  dc["model"]["top"]["motor_inertia_kgm2"] = 10;
  ExpectRootsAreTheZerosOfTheClosedForm(dc, "undamped string in 2 pieces, DC motor through a rigid gear");
}

// The top-drive laws of issue 35 on the coupled string: SoftTorque with explicit gains, Z-Torque matched to the
// pipe, the wave cancellation (tests/support/wave_cancelling_top.hpp), each of the last two also behind a 20 ms
// actuator delay (its retarded terms carried into the coupled system; 50 ms make Z-Torque's stiff speed loop,
// kp / J = 40 1/s, itself unstable with a root near 14 + 38i from which Newton on F, whose value there is 4e-8 of its
// size 0.01 away, leaves).
TEST(AxialTorsionalStability, TopDriveLawsAreTheZerosOfTheClosedForm) {
  nlohmann::json soft = Undamped(2);
  soft["model"]["top"]["type"] = "soft_torque";
  soft["model"]["top"]["feedback_gain_rad_per_Nms"] = 2e-4;
  soft["model"]["top"]["feedback_time_constant_s"] = 5;
  ExpectRootsAreTheZerosOfTheClosedForm(soft, "undamped string in 2 pieces, SoftTorque top");
  nlohmann::json z = Undamped(2);
  z["model"]["top"]["type"] = "z_torque";
  z["model"]["top"]["feedback_time_constant_s"] = 5;
  ExpectRootsAreTheZerosOfTheClosedForm(z, "undamped string in 2 pieces, Z-Torque top");
  z["model"]["top"]["actuator_delay_s"] = 0.02;
  ExpectRootsAreTheZerosOfTheClosedForm(z, "undamped string in 2 pieces, Z-Torque top behind 20 ms");
  nlohmann::json wave = Undamped(2);
  wave["model"]["top"].erase("ki_Nm_per_rad");
  wave["model"]["top"].update({{"type", "wave_cancellation"}, {"speed_loop_corner_rad_s", 0.2}});
  ExpectRootsAreTheZerosOfTheClosedForm(wave, "undamped string in 2 pieces, wave-cancelling top");
  wave["model"]["top"]["actuator_delay_s"] = 0.02;
  ExpectRootsAreTheZerosOfTheClosedForm(wave, "undamped string in 2 pieces, wave-cancelling top behind 20 ms");
}

// The hoist's dashpot to the block paying out at the steady rate (hoist/damping_Ns_per_m), matched to the axial
// impedance: Y_top = M_h s + c_h.
TEST(AxialTorsionalStability, HoistDashpotIsTheZeroOfTheClosedForm) {
  nlohmann::json doc = Undamped(2);
  const ClosedForm plain(doc);
  doc["model"]["hoist"]["damping_Ns_per_m"] = plain.za;
  ExpectRootsAreTheZerosOfTheClosedForm(doc, "undamped string in 2 pieces, hoist dashpot c_h = Z_a");
}

// The top drive hanging from the two-mass hoisting rig of json-cases/hoist-rig.json (its derrick and block modes near
// 23.8 and 62.7 rad/s join the string's).
TEST(AxialTorsionalStability, HoistingRigIsTheZeroOfTheClosedForm) {
  const nlohmann::json rig = testing::LoadCase("hoist-rig");
  nlohmann::json doc = Undamped(2);
  doc["model"]["hoist"]["rig"] = rig["model"]["hoist"]["rig"];
  doc["model"]["hoist"]["rig"].erase("cable_tension_change_N");
  ExpectRootsAreTheZerosOfTheClosedForm(doc, "undamped string in 2 pieces, hoisting rig");
}

// The same rig paying out its line by json-cases/hoist-drawworks.json's drawworks (a 30 000 kg m^2 drum at 0.04 m of
// line per radian, 50:1, the top's induction machine): the drum's speed and the motor's four fluxes join the states.
TEST(AxialTorsionalStability, DrawworksIsTheZeroOfTheClosedForm) {
  const nlohmann::json drawworks = testing::LoadCase("hoist-drawworks");
  nlohmann::json doc = Undamped(2);
  doc["model"]["hoist"]["rig"] = drawworks["model"]["hoist"]["rig"];
  doc["model"]["hoist"]["rig"].erase("cable_tension_change_N");
  doc["model"]["hoist"]["rig"]["drawworks"].erase("supply_change_Hz");
  const auto points = Linearize(doc);
  ASSERT_EQ(points.size(), 1u);
  const auto& names = points[0].state_names;
  EXPECT_NE(std::find(names.begin(), names.end(), "drawworks_drum_speed_rad_s"), names.end());
  ExpectRootsAreTheZerosOfTheClosedForm(doc, "undamped string in 2 pieces, hoisting rig with its drawworks");
}

// Without the rig's dampers and with the string's pull on the hoist negligible (hoist, block, derrick and both
// stiffnesses a million times larger: the same frequencies), two roots sit at the rig's undamped natural frequencies
// with the top drive's mass on the block (model::HoistRig::NaturalFrequencies).
TEST(AxialTorsionalStability, HeavyHoistingRigRingsAtItsTwoMassFrequencies) {
  const nlohmann::json rig = testing::LoadCase("hoist-rig");
  nlohmann::json doc = Undamped(2);
  auto& r = doc["model"]["hoist"]["rig"] = rig["model"]["hoist"]["rig"];
  r.erase("cable_tension_change_N");
  const double scale = 1e6;
  for (const char* key : {"derrick_mass_kg", "block_mass_kg", "ground_stiffness_N_per_m", "cable_stiffness_N_per_m"})
    r[key] = r[key].get<double>() * scale;
  r["derrick_damping_Ns_per_m"] = 0;
  r["block_damping_Ns_per_m"] = 0;
  doc["model"]["hoist"]["mass_kg"] = doc["model"]["hoist"]["mass_kg"].get<double>() * scale;
  model::HoistRig two_mass;
  two_mass.derrick_mass = r["derrick_mass_kg"], two_mass.block_mass = r["block_mass_kg"];
  two_mass.ground_stiffness = r["ground_stiffness_N_per_m"], two_mass.cable_stiffness = r["cable_stiffness_N_per_m"];
  const auto frequencies = two_mass.NaturalFrequencies(doc["model"]["hoist"]["mass_kg"].get<double>());
  const auto points = Linearize(doc);
  ASSERT_EQ(points.size(), 1u);
  analysis::SpectrumOptions o;
  o.im_max = 80;
  const analysis::Spectrum sp = analysis::ComputeSpectrum(points[0].system, o);
  for (const double w : frequencies) {
    double nearest = INFINITY;
    Complex at;
    for (const auto& root : sp.roots)
      if (std::abs(root.s - Complex(0, w)) < nearest) nearest = std::abs(root.s - Complex(0, w)), at = root.s;
    std::printf("[ measured ] heavy rig: two-mass frequency %.8f rad/s, nearest root %.3e%+.8fi (distance %.2e)\n", w,
                at.real(), at.imag(), nearest);
    EXPECT_LT(nearest, 1e-6 * w) << w;
  }
}

// Growth rate of a channel's component at angular frequency omega over [t0, t1]: the Hann-windowed Fourier amplitude
// over windows of four periods (or `window` s) centred every 0.05 s, least-squares slope of the logs. A mode
// e^{(sigma + i omega) t} gives sigma; the other modes leak little through the window (a string's harmonics, about
// pi / tau apart, need a window of a few 2 tau).
double ModeGrowthRate(const RunResult& run, const std::string& channel, double omega, double t0, double t1,
                      double window = 0) {
  const std::vector<double>& x = run.channel(channel).values;
  if (window == 0) window = 8 * kPi / omega;
  double sx = 0, sy = 0, sxx = 0, sxy = 0, mean = 0;
  for (double v : x) mean += v / x.size();
  int n = 0;
  for (double centre = t0 + 0.5 * window; centre <= t1 - 0.5 * window; centre += 0.05) {
    Complex sum = 0;
    for (std::size_t i = 0; i < run.time_s.size(); ++i) {
      const double u = (run.time_s[i] - centre) / window;
      if (std::abs(u) > 0.5) continue;
      sum += (x[i] - mean) * std::pow(std::cos(kPi * u), 2) * std::polar(1.0, -omega * run.time_s[i]);
    }
    const double y = std::log(std::abs(sum));
    sx += centre, sy += y, sxx += centre * centre, sxy += centre * y;
    ++n;
  }
  EXPECT_GE(n, 10);
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// A set-point blip of 1e-6 rad/s for 0.1 s at w [rad/s] sets every mode going; while the bit's axial speed stays far
// from zero (the wear flats' contact force is constant only while the bit advances) the run is linear, and the
// rightmost root's mode grows at its real part in the bit's axial speed (and, if asked, in its angular speed).
// Held to `tolerance`, by default 3 % + 3e-3 1/s.
void ExpectRightmostRootGrowsAsSimulated(nlohmann::json doc, double w, double t0, double t1, bool in_bit_speed,
                                         const std::string& what, double tolerance = -1) {
  doc["model"]["string"]["subsections"] = 5;
  doc["model"]["top"]["speed_rad_s"] = {{"knots", {{0, w}, {0.05, w + 1e-6}, {0.1, w}}}};
  doc["simulation"] = {{"duration_s", t1}, {"output_interval_s", 2e-3}, {"abs_tol", 1e-12}, {"rel_tol", 1e-10}};
  doc["statistics"]["window_s"] = {0, t1};
  doc.erase("expect");
  if (doc["model"]["hoist"].contains("rig")) doc["model"]["hoist"]["rig"].erase("cable_tension_change_N");
  const Case c = ParseCase(doc);
  const auto points = c.model->Linearize();
  ASSERT_EQ(points.size(), 1u) << what;
  const analysis::Spectrum sp = analysis::ComputeSpectrum(points[0].system);
  const analysis::CharacteristicRoot& r = sp.roots.front();
  const CaseRun run = RunCase(c);
  const auto& v = run.result.channel("bit_axial_speed_m_s").values;
  double largest = 0;
  for (std::size_t i = 0; i < v.size(); ++i) largest = std::max(largest, std::abs(v[i] - v.front()));
  const double axial = ModeGrowthRate(run.result, "bit_axial_speed_m_s", r.s.imag(), t0, t1);
  const double torsional = ModeGrowthRate(run.result, "bit_rpm", r.s.imag(), t0, t1);
  std::printf("[ measured ] %s, 5 pieces: rightmost root %.6f%+.6fi; simulated growth at its frequency over [%.1f, "
              "%.1f] s: %.6f 1/s (axial speed), %.6f 1/s (bit speed); largest axial speed deviation %.2e m/s (V0 = "
              "%.2e)\n", what.c_str(), r.s.real(), r.s.imag(), t0, t1, axial, torsional, largest, v.front());
  EXPECT_LT(largest, 0.1 * v.front()) << what << ": the run left the linear range";
  if (tolerance < 0) tolerance = 0.03 * std::abs(r.s.real()) + 3e-3;
  EXPECT_NEAR(axial, r.s.real(), tolerance) << what;
  if (in_bit_speed) {
    EXPECT_NEAR(torsional, r.s.real(), tolerance) << what;
  }
}

// The regenerative axial oscillation of RGD in the baseline. At 150 rpm the bit speed's component at 42.8 rad/s is
// small beside the slowly decaying torsional modes, whose leakage through the window bends its slope (measured 0.389
// against 0.420): checked in the axial speed only.
TEST(AxialTorsionalStability, RightmostRootIsTheGrowthRateOfTheSimulatedCoupledModel) {
  ExpectRightmostRootGrowsAsSimulated(Baseline(), 2 * kPi, 1, 4, true, "60 rpm");
  ExpectRightmostRootGrowsAsSimulated(Baseline(), 5 * kPi, 2, 14, false, "150 rpm");
}

// Kelvin-Voigt dashpots across the pieces of both channels, and the top drive hanging from the hoisting rig: the
// rightmost root grows as the simulation does, to 1e-3 1/s over [2.5, 5] s (over [1, 4] s the decaying modes still
// leak through the window: 3.3709 and 3.3343 against 3.3594 with the dashpots).
TEST(AxialTorsionalStability, KelvinVoigtAndRigRightmostRootIsTheGrowthRateOfTheSimulation) {
  nlohmann::json kv = Baseline();
  kv["model"]["string"]["kelvin_voigt_s"] = 0.024;
  kv["model"]["string"]["axial_kelvin_voigt_s"] = 0.002;
  ExpectRightmostRootGrowsAsSimulated(kv, 2 * kPi, 2.5, 5, true, "Kelvin-Voigt, 60 rpm", 1e-3);
  const nlohmann::json rig = testing::LoadCase("hoist-rig");
  ExpectRightmostRootGrowsAsSimulated(rig, 2 * kPi, 2.5, 5, true, "hoisting rig, 60 rpm", 1e-3);
}

// The induction motor on the slip-compensated V/f supply behind the rig's compliant gear
// (json-cases/baseline-induction-rig-60rpm.json) without the axial coupling, whose regenerative mode would swamp the
// torsional ones: after a 1e-6 rad/s set-point blip the bit speed's stick-slip mode and the next one decay at the
// real parts of their roots. The stick-slip mode is held to 2e-5 1/s: with the motor's torque taken as the PI's output
// (no fluxes) its root moves by 7.4e-5.
// The case without the axial coupling, in 5 pieces, at top speed `speed`, run for 30 s at tolerances 1e-10.
Case UncoupledRun(nlohmann::json doc, const nlohmann::json& speed) {
  doc["model"]["axial_coupling"] = false;
  doc["model"]["string"]["subsections"] = 5;
  doc["model"]["top"]["speed_rad_s"] = speed;
  doc["simulation"] = {{"duration_s", 30}, {"output_interval_s", 2e-3}, {"abs_tol", 1e-12}, {"rel_tol", 1e-10}};
  doc["statistics"]["window_s"] = {0, 30};
  doc.erase("expect");
  return ParseCase(doc);
}

TEST(AxialTorsionalStability, InductionMotorTopsTorsionalModesDecayAsSimulated) {
  const double w = 2 * kPi;
  const Case c = UncoupledRun(io::LoadJsonFile(std::string(DRILLWAVE_SOURCE_DIR) +
                                               "/json-cases/baseline-induction-rig-60rpm.json"),
                              {{"knots", {{0, w}, {0.05, w + 1e-6}, {0.1, w}}}});
  const auto points = c.model->Linearize();
  ASSERT_EQ(points.size(), 1u);
  const analysis::Spectrum sp = analysis::ComputeSpectrum(points[0].system);
  const CaseRun run = RunCase(c);
  struct Mode {
    double im_min, im_max, t0, t1, tolerance;
  };
  for (const Mode& m : {Mode{1, 3, 2, 30, 2e-5}, Mode{4, 8, 1, 15, 3e-3}}) {
    const auto r = std::find_if(sp.roots.begin(), sp.roots.end(), [&](const analysis::CharacteristicRoot& x) {
      return x.s.imag() > m.im_min && x.s.imag() < m.im_max;
    });
    ASSERT_NE(r, sp.roots.end());
    const double measured = ModeGrowthRate(run.result, "bit_rpm", r->s.imag(), m.t0, m.t1);
    std::printf("[ measured ] induction motor behind the compliant gear, no axial coupling: root %.6f%+.6fi, "
                "simulated decay at its frequency over [%.0f, %.0f] s %.6f 1/s\n", r->s.real(), r->s.imag(), m.t0, m.t1,
                measured);
    EXPECT_NEAR(measured, r->s.real(), m.tolerance) << r->s;
  }
}

// The unbalanced BHA of json-cases/saldivar-whirl.json at the baseline's bit without the axial coupling (whose
// regenerative mode would swamp the others): the run starts in steady drilling with the BHA at rest in the middle, the
// steady whirl's radius away, and the bit speed's stick-slip mode and the whirl radius's two modes (in the frame
// turning with the bit: the lateral frequency minus and plus the bit speed) decay at the real parts of their roots.
// At the top speed w with the unbalance mass m (at e = 0.05 m): the steady whirl radius m e w^2 / |k - M_t w^2 + i c w|
// (the seed's Jeffcott rotor, M_t = M + m) is 9.4e-5 m at 60 rpm with 50 kg, and 4.4 mm, 47 times more, at 12 rad/s,
// nearer the lateral resonance sqrt(k / M_t) = 15.3 rad/s, with 300 kg.
void ExpectUnbalancedModesDecayAsSimulated(double w, double unbalance_mass) {
  nlohmann::json doc = Baseline();
  doc["model"]["bit"]["unbalance"] = {{"lateral_mass_kg", 5000}, {"lateral_stiffness_N_per_m", 1.246e6},
                                      {"lateral_damping_Ns_per_m", 7900}, {"unbalance_mass_kg", unbalance_mass},
                                      {"eccentricity_m", 0.05}};
  const Case c = UncoupledRun(doc, w);
  const auto points = c.model->Linearize();
  ASSERT_EQ(points.size(), 1u);
  const analysis::Spectrum sp = analysis::ComputeSpectrum(points[0].system);
  const CaseRun run = RunCase(c);
  // The modes nearest to: the stick-slip mode without the unbalance, and the fixed frame's lateral roots
  // -c / 2 M_t + i w_d shifted by -i w and +i w.
  const double mt = 5000 + unbalance_mass, decay = -7900 / (2 * mt), wd = std::sqrt(1.246e6 / mt - decay * decay);
  const double radius = unbalance_mass * 0.05 * w * w / std::abs(Complex(1.246e6 - mt * w * w, 7900 * w));
  struct Mode {
    Complex near;
    const char* channel;
    double t0, t1;
  };
  // The stick-slip mode only at 60 rpm: at 12 rad/s the string's torsional modes are damped far faster than the
  // whirl's and leave no clean window.
  std::vector<Mode> modes{{{decay, wd - w}, "lateral_displacement_m", 0.5, w < 7 ? 10.5 : 12.0},
                          {{decay, wd + w}, "lateral_displacement_m", 0.5, 10.5}};
  if (w < 7) modes.insert(modes.begin(), Mode{{-0.02, 1.86}, "bit_rpm", 5, 30});
  for (const Mode& m : modes) {
    const auto r = std::min_element(sp.roots.begin(), sp.roots.end(), [&](const auto& x, const auto& y) {
      return std::abs(x.s - m.near) < std::abs(y.s - m.near);
    });
    ASSERT_LT(std::abs(r->s - m.near), 1.0) << m.near;
    const double measured = ModeGrowthRate(run.result, m.channel, r->s.imag(), m.t0, m.t1);
    std::printf("[ measured ] unbalanced BHA at %.2f rad/s, steady whirl radius %.3g m, no axial coupling: root "
                "%.6f%+.6fi, simulated growth at its frequency in %s over [%.1f, %.1f] s %.6f 1/s\n", w, radius,
                r->s.real(), r->s.imag(), m.channel, m.t0, m.t1, measured);
    EXPECT_NEAR(measured, r->s.real(), 0.03 * std::abs(r->s.real()) + 3e-3) << r->s;
  }
}

TEST(AxialTorsionalStability, UnbalancedBhaModesDecayAsSimulated) { ExpectUnbalancedModesDecayAsSimulated(2 * kPi, 50); }

TEST(AxialTorsionalStability, UnbalancedBhaModesDecayAsSimulatedAtALargeWhirl) {
  ExpectUnbalancedModesDecayAsSimulated(12, 300);
}

// The top-drive laws on the coupled kind's torsion, with the Stribeck rock of json-cases/baseline-stribeck.json at
// 60 rpm and no axial coupling (whose regenerative mode would swamp the torsional ones): velocity weakening makes the
// stiff PI's stick-slip mode grow; SoftTorque (g = 5e-4 rad/s per N m, tau_f = 5 s) damps it, also behind a 20 ms
// actuator delay, which makes a harmonic of the string grow instead (the rightmost root, near 69 rad/s); Z-Torque damps
// the stick-slip mode fast and leaves the harmonics near 183 rad/s the slowest to decay. After a set-point blip the
// bit speed's component at each root's frequency grows or decays at the root's real part: the run and the
// linearization `stability` uses agree with the law, its filter and its delay in the loop. The harmonics, 5 rad/s
// apart (pi / tau), are read through 3-s windows. Held to 3 % + 3e-3 1/s; the relative errors are printed.
TEST(AxialTorsionalStability, TopDriveLawsModesGrowOrDecayAsSimulated) {
  const nlohmann::json stribeck =
      testing::LoadCase("baseline-stribeck");
  const double w = 2 * kPi;
  struct Law {
    const char* what;
    nlohmann::json top;  // fields set on the case's top
    double blip, im_min, im_max, t0, t1, window;
  };
  const nlohmann::json soft = {{"type", "soft_torque"}, {"feedback_gain_rad_per_Nms", 5e-4},
                               {"feedback_time_constant_s", 5}};
  nlohmann::json delayed = soft;
  delayed["actuator_delay_s"] = 0.02;
  const nlohmann::json z = {{"type", "z_torque"}, {"feedback_time_constant_s", 5}};
  // The sliding mode on Z-Torque's command, its layer's gain J eta / phi the stiff PI's kp (J eta = 30 kN m over
  // 0.3 rad/s): kicked within its layer it is the PI of SlidingMode::InLayer, which the linearization holds (its
  // stick-slip mode decays at 1.62 1/s, too fast to read through a window; the slowest harmonic is read).
  const nlohmann::json sliding = {{"type", "sliding_mode"},      {"kp_Nms_per_rad", nullptr},
                                  {"ki_Nm_per_rad", nullptr},    {"feedback_time_constant_s", 5},
                                  {"surface_corner_rad_s", 0.2}, {"reaching_rate_rad_s2", 12},
                                  {"boundary_layer_rad_s", 0.3}};
  // The wave cancellation (its speed loop's corner 0.3 1/s) low-passed at tf 0.2 s behind 100 ms, kp 5000: the first
  // harmonic grows, as in the torsional_wave kind. (Exact and undelayed, every mode decays; its harmonics, at 2.4 1/s
  // among larger, slower modes 4-6 rad/s apart, read 7 % slower: this window cannot tell that from leakage.)
  const nlohmann::json filtered = {{"type", "wave_cancellation"},       {"ki_Nm_per_rad", nullptr},
                                   {"speed_loop_corner_rad_s", 0.3},    {"wave_filter_time_constant_s", 0.2},
                                   {"actuator_delay_s", 0.1},           {"kp_Nms_per_rad", 5000}};
  const Law laws[] = {{"stiff PI, stick-slip mode", {{"type", "top_drive"}}, 1e-6, 1, 3, 5, 30, 0},
                      {"SoftTorque, stick-slip mode", soft, 1e-3, 1, 3, 5, 30, 0},
                      {"SoftTorque behind 20 ms, stick-slip mode", delayed, 1e-3, 1, 3, 5, 30, 0},
                      {"SoftTorque behind 20 ms, rightmost root", delayed, 1e-6, 60, 75, 2, 15, 3},
                      {"Z-Torque, rightmost root", z, 1e-3, 175, 190, 1, 15, 3},
                      {"sliding mode, rightmost root", sliding, 1e-3, 175, 190, 1, 15, 3},
                      {"wave cancellation low-passed behind 100 ms, rightmost root", filtered, 1e-6, 20, 26, 2, 15, 3}};
  for (const Law& law : laws) {
    nlohmann::json doc = stribeck;
    doc["model"]["top"].update(law.top);
    for (const char* gain : {"kp_Nms_per_rad", "ki_Nm_per_rad"})  // null: the law has none of its own
      if (doc["model"]["top"][gain].is_null()) doc["model"]["top"].erase(gain);
    const Case c = UncoupledRun(doc, {{"knots", {{0, w}, {0.05, w + law.blip}, {0.1, w}}}});
    const auto points = c.model->Linearize();
    ASSERT_EQ(points.size(), 1u) << law.what;
    analysis::SpectrumOptions o;
    o.im_max = 200;
    const analysis::Spectrum sp = analysis::ComputeSpectrum(points[0].system, o);
    const auto r = std::find_if(sp.roots.begin(), sp.roots.end(), [&](const analysis::CharacteristicRoot& x) {
      return x.s.imag() > law.im_min && x.s.imag() < law.im_max;
    });
    ASSERT_NE(r, sp.roots.end()) << law.what;
    const CaseRun run = RunCase(c);
    const double measured = ModeGrowthRate(run.result, "bit_rpm", r->s.imag(), law.t0, law.t1, law.window);
    std::printf("[ measured ] %s at 60 rpm, no axial coupling: root %.6f%+.6fi, simulated growth at its frequency over "
                "[%.0f, %.0f] s %.6f 1/s (relative error %.1e); rightmost root %.6f%+.6fi\n", law.what, r->s.real(),
                r->s.imag(), law.t0, law.t1, measured, std::abs(measured - r->s.real()) / std::abs(r->s.real()),
                sp.roots.front().s.real(), sp.roots.front().s.imag());
    EXPECT_NEAR(measured, r->s.real(), 0.03 * std::abs(r->s.real()) + 3e-3) << law.what;
  }
}

// The chapter's contact laws (rock/contact, bitrock/contact_law.hpp) in the linearization: the slope of F at the
// steady bit speed (and, with eq. 2.33's cutting torque, the slope and the gain F^2 of the cut) moves the roots.
// Without the axial coupling, at 60 rpm, the stick-slip mode's root against the bit speed's growth at its frequency
// after a 1e-6 rad/s set-point blip: tanh_hump falling past its hump (velocity weakening, like baseline-stribeck's
// friction) undamps it, sqrt_regularized with a wide eps = 2 rad/s and eq. 2.33 damps it. With the coupling, the
// regenerative mode's root against the bit's axial speed, as in RightmostRootIsTheGrowthRateOfTheSimulatedCoupledModel.
// Held to 3 % + 3e-3 1/s; the relative errors are printed.
const nlohmann::json kTanhHump = {{"law", "tanh_hump"}, {"beta", 1}, {"gamma1", 1.66}, {"gamma2", 1}};
const nlohmann::json kWideSquared = {
    {"law", "sqrt_regularized"}, {"epsilon_rad_s", 2}, {"cutting_torque", "f_squared"}};

TEST(AxialTorsionalStability, ContactLawsSlopesMoveTheStickSlipModeAsSimulated) {
  const double w = 2 * kPi;
  struct Law {
    const char* what;
    nlohmann::json contact;
    double t0, t1, window;  // over a few decay times, in windows of four periods (0) or shorter for a fast decay
  };
  for (const Law& law : {Law{"set-valued contact (RGD)", nullptr, 5, 30, 0}, Law{"tanh_hump", kTanhHump, 5, 30, 0},
                         Law{"sqrt_regularized, eps 2 rad/s, eq. 2.33", kWideSquared, 1, 10, 3}}) {
    nlohmann::json doc = Baseline();
    if (!law.contact.is_null()) doc["model"]["rock"]["contact"] = law.contact;
    const Case c = UncoupledRun(doc, {{"knots", {{0, w}, {0.05, w + 1e-6}, {0.1, w}}}});
    const auto points = c.model->Linearize();
    ASSERT_EQ(points.size(), 1u) << law.what;
    const analysis::Spectrum sp = analysis::ComputeSpectrum(points[0].system);
    const auto r = std::find_if(sp.roots.begin(), sp.roots.end(),
                                [](const analysis::CharacteristicRoot& x) { return x.s.imag() > 1 && x.s.imag() < 3; });
    ASSERT_NE(r, sp.roots.end()) << law.what;
    const CaseRun run = RunCase(c);
    const double measured = ModeGrowthRate(run.result, "bit_rpm", r->s.imag(), law.t0, law.t1, law.window);
    std::printf("[ measured ] %s at 60 rpm, no axial coupling: bit torque slope %.4f N m s/rad, stick-slip root "
                "%.6f%+.6fi, simulated growth at its frequency over [%.0f, %.0f] s %.6f 1/s (relative error %.1e)\n",
                law.what, points[0].steady_state.at("bit_torque_slope_Nms_per_rad").get<double>(), r->s.real(),
                r->s.imag(), law.t0, law.t1, measured, std::abs(measured - r->s.real()) / std::abs(r->s.real()));
    EXPECT_NEAR(measured, r->s.real(), 0.03 * std::abs(r->s.real()) + 3e-3) << law.what;
  }
}

TEST(AxialTorsionalStability, ContactLawsRightmostRootIsTheGrowthRateOfTheSimulatedCoupledModel) {
  for (const nlohmann::json& contact : {kTanhHump, kWideSquared}) {
    nlohmann::json doc = Baseline();
    doc["model"]["rock"]["contact"] = contact;
    ExpectRightmostRootGrowsAsSimulated(doc, 2 * kPi, 1, 4, true, "60 rpm, contact " + contact.dump());
  }
}

}  // namespace
}  // namespace drillwave::cases
