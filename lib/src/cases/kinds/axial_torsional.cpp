// Model kind "axial_torsional": coupled axial and torsional waves with the Richard-Germay-Detournay bit-rock law and
// the cut delay t_n (the model: axial_torsional_model.hpp; its run: axial_torsional_run.cpp). Here: the JSON reader,
// the kind's schema and the linearization at steady drilling.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "axial_torsional_model.hpp"
#include "rgd_reader.hpp"
#include "drillwave/analysis/axial_torsional_linearization.hpp"
#include "drillwave/cases/kinds.hpp"
#include "drillwave/core/error.hpp"
#include "string_components.hpp"
#include "top_components.hpp"

namespace drillwave::cases {
namespace {

// The model this file reads and linearizes.
using axial_torsional::Channel;
using axial_torsional::CheckSteadyStart;
using axial_torsional::Model;
using axial_torsional::Simulate;
using axial_torsional::Steady;
using axial_torsional::SteadyDrilling;
using io::JsonReader;
using Range = io::Range;

// hoist/rig: the two-mass hoisting rig (model::HoistRig).
model::HoistRig ReadHoistRig(const JsonReader& r) {
  model::HoistRig rig;
  rig.derrick_mass = r.Number("derrick_mass_kg", Range::Positive());
  rig.block_mass = r.Number("block_mass_kg", Range::Positive());
  rig.derrick_damping = r.Number("derrick_damping_Ns_per_m", Range::NonNegative());
  rig.block_damping = r.Number("block_damping_Ns_per_m", Range::NonNegative());
  rig.ground_stiffness = r.Number("ground_stiffness_N_per_m", Range::Positive());
  rig.cable_stiffness = r.Number("cable_stiffness_N_per_m", Range::Positive());
  if (r.Has("cable_tension_change_N"))
    rig.tension_change = model::Schedule::FromJson(r.Raw("cable_tension_change_N"), r.PathOf("cable_tension_change_N"));
  if (r.Has("drawworks")) {  // the drawworks' induction motor paying out the line (chapter eq. 2.37)
    const JsonReader d = r.Object("drawworks");
    model::Drawworks w;
    w.line_radius = d.Number("line_radius_m", Range::Positive());
    w.inertia = d.Number("inertia_kgm2", Range::Positive());
    w.gear_ratio = d.Number("gear_ratio", Range::Positive(), 1.0);
    w.motor = ReadInductionMotor(d.Object("induction_motor"));
    if (const std::string problem = w.motor.Problem(); !problem.empty())
      throw InputError(d.PathOf("induction_motor"), problem);
    if (d.Has("supply_change_Hz"))
      w.supply_change_hz = model::Schedule::FromJson(d.Raw("supply_change_Hz"), d.PathOf("supply_change_Hz"));
    d.Finish();
    rig.drawworks = w;
  }
  r.Finish();
  return rig;
}

// The induction motor and the gear of the top drive block (the DC motor is read beside them).
void ReadTopMotorAndGear(const JsonReader& top, Model& md) {
  if (top.Has("induction_motor")) {
    if (md.motor.on)
      throw InputError(top.PathOf("induction_motor"),
                       "expected either a DC motor (motor) or an induction motor, not both");
    md.induction_on = true;
    md.induction = ReadInductionMotor(top.Object("induction_motor"));
  }
  md.gear = ReadGear(top);
  md.motor.k *= md.gear.ratio;  // a DC motor's constant referred to the top drive: torque n K I, back-emf n K w
}

class AxialTorsionalModel : public PreparedModel {
 public:
  explicit AxialTorsionalModel(Model md) : md_(std::move(md)) {}
  // Steady drilling at the inputs' final values and its linearization (analysis/axial_torsional_linearization.hpp).
  std::vector<LinearizedOperatingPoint> Linearize() const override;
  RunResult Run(const RunSettings& settings) const override { return Simulate(md_, settings); }

 private:
  Model md_;
};

// A section of the string (the pipe, then the BHA): geometry, viscous damping per metre, sub-sections.
struct Section {
  double length, outer, inner, c_t, c_a;
  int pieces;
  double Area() const { return kPi / 4 * (outer * outer - inner * inner); }
  double Polar() const { return kPi / 32 * (std::pow(outer, 4) - std::pow(inner, 4)); }
};
struct StringSpec {
  double length = 0;              // top drive to bit
  std::vector<Section> sections;  // top to bottom
  double e_mod = 0, g_mod = 0, rho = 0, rho_mud = 0;
  double eta_t = 0, eta_a = 0;    // Kelvin-Voigt retardation times [s]
  double side_torque_per_m = 0, side_from = 0, side_to = 0;
};

// The torsional impedance G J / c = J sqrt(G rho) of a section's pieces.
double TorsionalImpedance(const StringSpec& sp, const Section& section) {
  return section.Polar() * std::sqrt(sp.g_mod * sp.rho);
}

// What this kind's top-drive law may not be: behind a motor the PI gives a voltage or a torque demand, not the top's
// torque; a delayed controller and the wave cancellation read the string torque from the wave arriving at the top
// alone (neither a compliant gear's twist nor Kelvin-Voigt dashpots), as in the torsional_wave kind.
void CheckTopDriveLaw(const JsonReader& top, const std::string& type, const StringSpec& string, const Model& md) {
  const model::TopDriveLaw& law = md.law;
  if (md.motor.on || md.induction_on) {
    const char* field = type != "top_drive" ? "type" : law.torque_limit > 0 ? "torque_limit_Nm" : nullptr;
    if (!field && law.actuator_delay_s > 0) field = "actuator_delay_s";
    if (field)
      throw InputError(top.PathOf(field), std::string("the PI drives ") + (md.motor.on ? "a DC motor (top/motor)" :
                                          "an induction motor (top/induction_motor)") + " here, not the top's torque: "
                                          "expected top/type top_drive without torque_limit_Nm or actuator_delay_s");
  }
  CheckWaveCancellationString(top, law, string.eta_t);
  if (law.actuator_delay_s > 0 && (md.gear.compliant() || string.eta_t > 0)) {
    const std::string with = md.gear.compliant() ? "a compliant gear" : "string/kelvin_voigt_s > 0";
    throw InputError(top.PathOf("actuator_delay_s"), "the delayed controller reads the string torque from the wave "
                                                     "arriving at the top alone: expected 0 with " + with);
  }
}

// One section below the pipe (the BHA, or a part of it: heavy-weight pipe, collars, ...).
Section ReadBha(const JsonReader& c, const Section& pipe, double string_length) {
  Section bha;
  bha.length = c.Number("length_m", Range::Positive());
  if (bha.length >= string_length)
    throw InputError(c.PathOf("length_m"), "expected less than the string's length_m = " +
                                               ReadableNumber(string_length) + " m (the BHA is its lowest part)");
  bha.outer = c.Number("outer_diameter_m", Range::Positive());
  bha.inner = c.Number("inner_diameter_m", Range::NonNegative());
  if (bha.inner >= bha.outer) throw InputError(c.PathOf("inner_diameter_m"), "expected a value below outer_diameter_m");
  bha.c_t = c.Number("torsional_damping_Nms_per_rad_m", Range::NonNegative(), pipe.c_t);
  bha.c_a = c.Number("axial_damping_Ns_per_m2", Range::NonNegative(), pipe.c_a);
  // By default pieces about as long as the pipe's, so that the travel times are near each other (the step is capped
  // at the shortest).
  const double pipe_piece = pipe.length / pipe.pieces;
  const int pieces = std::clamp(static_cast<int>(std::lround(bha.length / pipe_piece)), 1, 400);
  bha.pieces = c.Integer("subsections", 1, 400, pieces);
  c.Finish();
  return bha;
}

// The longest drill strings reach about 12 km (extended-reach wells of 12-13 km measured depth); 20 km, the bound
// of a sidecar's measured depth too, leaves room above them. Far longer strings are no drill string: their waves
// do not come back within a run, so the nodes' histories are never trimmed and grow with every step (1e9 m ran out of
// memory).
constexpr double kMaxStringLengthM = 20000;

StringSpec ReadString(const JsonReader& s) {
  StringSpec sp;
  Section pipe;
  sp.length = s.Number("length_m", Range{0, kMaxStringLengthM, true, false});
  pipe.outer = s.Number("outer_diameter_m", Range::Positive());
  pipe.inner = s.Number("inner_diameter_m", Range::NonNegative());
  if (pipe.inner >= pipe.outer)
    throw InputError(s.PathOf("inner_diameter_m"), "expected a value below outer_diameter_m");
  sp.e_mod = s.Number("youngs_modulus_Pa", Range::Positive());
  sp.g_mod = s.Number("shear_modulus_Pa", Range::Positive());
  sp.rho = s.Number("density_kg_m3", Range::Positive());
  sp.rho_mud = s.Number("mud_density_kg_m3", Range::NonNegative(), 0.0);
  if (sp.rho_mud >= sp.rho) throw InputError(s.PathOf("mud_density_kg_m3"), "expected a value below density_kg_m3");
  pipe.c_t = s.Number("torsional_damping_Nms_per_rad_m", Range::NonNegative());
  pipe.c_a = s.Number("axial_damping_Ns_per_m2", Range::NonNegative());
  sp.eta_t = ReadKelvinVoigt(s);
  sp.eta_a = ReadKelvinVoigt(s, "axial_kelvin_voigt_s");
  if (s.Has("side_friction")) {
    const JsonReader f = s.Object("side_friction");
    sp.side_torque_per_m = f.Number("torque_per_m_Nm", Range::NonNegative());
    sp.side_from = f.Number("from_m", Range::NonNegative(), 0.0);
    sp.side_to = f.Number("to_m", Range::NonNegative(), 1e300);
    if (sp.side_to <= sp.side_from) throw InputError(f.PathOf("to_m"), "expected a depth below from_m");
    f.Finish();
  }
  pipe.pieces = s.Integer("subsections", 2, 400, 20);
  pipe.length = sp.length;
  sp.sections = {pipe};
  if (s.Has("bha")) {  // one section, or several top to bottom (heavy-weight pipe, collars, ...)
    const bool several = s.Raw("bha").is_array();
    const std::vector<JsonReader> parts = several ? s.ObjectArray("bha") : std::vector<JsonReader>{s.Object("bha")};
    if (parts.empty()) throw InputError(s.PathOf("bha"), "expected at least one section");
    double below_pipe = 0;
    for (const JsonReader& part : parts) below_pipe += part.Number("length_m", Range::Positive());
    if (below_pipe >= sp.length && several)
      throw InputError(s.PathOf("bha"), "expected sections shorter together (" + ReadableNumber(below_pipe) +
                                            " m) than the string's length_m = " + ReadableNumber(sp.length) + " m");
    sp.sections[0].length = std::max(sp.length - below_pipe, 0.0);  // (a single section too long: ReadBha says so)
    for (const JsonReader& part : parts) sp.sections.push_back(ReadBha(part, sp.sections[0], sp.length));
  }
  s.Finish();
  return sp;
}

// Channels of sub-sections, pipe then BHA: damping and buoyant weight of each piece lumped at its two nodes (half at
// each), which keeps the d'Alembert reduction exact inside every piece.
void BuildChannels(const StringSpec& sp, double g, Model& md) {
  md.m = 0;
  for (const Section& section : sp.sections) md.m += section.pieces;
  for (Channel* ch : {&md.torsion, &md.axial}) {
    ch->z.assign(md.m, 0.0), ch->tau.assign(md.m, 0.0);
    ch->damping.assign(md.m + 1, 0.0), ch->load.assign(md.m + 1, 0.0), ch->coulomb.assign(md.m + 1, 0.0);
  }
  if (sp.eta_t > 0) md.torsion.kv.assign(md.m, 0.0);
  if (sp.eta_a > 0) md.axial.kv.assign(md.m, 0.0);
  int k = 0;
  double depth = 0;  // of the top of piece k
  for (const Section& section : sp.sections) {
    const double piece = section.length / section.pieces, weight_per_m = (sp.rho - sp.rho_mud) * section.Area() * g;
    for (int i = 0; i < section.pieces; ++i, ++k, depth += piece) {
      md.torsion.z[k] = TorsionalImpedance(sp, section);
      md.torsion.tau[k] = piece / std::sqrt(sp.g_mod / sp.rho);
      md.axial.z[k] = section.Area() * std::sqrt(sp.e_mod * sp.rho);
      md.axial.tau[k] = piece / std::sqrt(sp.e_mod / sp.rho);
      if (md.torsion.kelvin_voigt()) md.torsion.kv[k] = sp.eta_t * sp.g_mod * section.Polar() / piece;
      if (md.axial.kelvin_voigt()) md.axial.kv[k] = sp.eta_a * sp.e_mod * section.Area() / piece;
      for (int end = 0; end < 2; ++end) {
        const int j = k + end;
        md.torsion.damping[j] += 0.5 * section.c_t * piece;
        md.axial.damping[j] += 0.5 * section.c_a * piece;
        md.axial.load[j] += 0.5 * weight_per_m * piece;
        // Side friction between from_m and to_m on the internal (massless) nodes, over the half piece each stands for.
        if (j == 0 || j == md.m) continue;
        const double lo = std::max(depth + 0.5 * end * piece, sp.side_from);
        const double hi = std::min(depth + 0.5 * (end + 1) * piece, sp.side_to);
        md.torsion.coulomb[j] += sp.side_torque_per_m * std::max(0.0, hi - lo);
      }
    }
  }
}

// The axial balance of steady drilling (chapter eq. 2.23 at rest in the moving frame): H = W_b - W0 - C V0, with the
// buoyant weight W_b of string and bit, the viscous drag C = sum c_a L per unit rate of penetration, and
// V0 = d0 Omega / 2 pi, d0 = (W0 - a sigma l) / (a zeta eps) (SteadyDrilling). Solved for H or, linear in W0, for W0.
struct HoistBalance {
  double buoyant_weight = 0, drag_per_speed = 0;
  double RopPerWob(double omega, const Model& md) const { return omega / (2 * kPi) / md.CutWeightPerDepth(); }
  double HookForce(const Model& md, double omega, double wob) const {
    return buoyant_weight - wob - drag_per_speed * RopPerWob(omega, md) * std::max(wob - md.ContactForce(), 0.0);
  }
  double WeightOnBit(const Model& md, double omega, double hook) const {
    const double kappa = drag_per_speed * RopPerWob(omega, md);
    return (buoyant_weight - hook + kappa * md.ContactForce()) / (1 + kappa);
  }
};
HoistBalance Balance(const Model& md, const StringSpec& string) {
  HoistBalance b;
  for (double l : md.axial.load) b.buoyant_weight += l;
  for (const Section& section : string.sections) b.drag_per_speed += section.c_a * section.length;
  return b;
}

// A dashpot at the top (the hoist's, to a block moving at the steady speed) adds to the top node's damping: the
// linearization sees speed perturbations only.
analysis::WaveChannel LinearChannel(const Channel& ch, double top_inertia, double bit_inertia,
                                    double top_dashpot = 0) {
  analysis::WaveChannel linear{ch.z, ch.tau, ch.damping, top_inertia, bit_inertia, ch.kv};
  linear.node_damping.front() += top_dashpot;
  return linear;
}

// The top drive's motor and gear as the linearization's network top. The DC motor's voltage R/K u_PI + K Omega_ref is
// a PI in volts (gains R/K kp, R/K ki) plus a constant; its constant, referred here (n K), goes back to the motor's
// own K, which the network refers again.
void DescribeTopDrive(const Model& md, analysis::AxialTorsionalString& string) {
  string.gear = md.gear;
  string.top_law = md.law;
  if (md.motor.on) {
    string.top_drive = waves::Drive::kDcMotorSpeed;
    string.dc_motor = {md.motor.k / md.gear.ratio, md.motor.resistance, md.motor.inductance, 0};
    string.pi.kp = md.motor.resistance / md.motor.k * md.pi.kp;
    string.pi.ki = md.motor.resistance / md.motor.k * md.pi.ki;
  } else if (md.induction_on) {
    string.top_drive = waves::Drive::kInductionMotorSpeed;
    string.induction_motor = md.induction;
  }
}

// What the top drive supplies in steady drilling at omega: the bit's torque and every node's damping and Coulomb
// friction (as InitializeWaves balances the top section).
double SteadyTopTorque(const Channel& torsion, double bit_torque, double omega) {
  double torque = bit_torque;
  for (std::size_t j = 0; j < torsion.damping.size(); ++j)
    torque += torsion.damping[j] * omega - torsion.load[j] + (j > 0 ? torsion.coulomb[j] : 0.0);
  return torque;
}

std::vector<LinearizedOperatingPoint> AxialTorsionalModel::Linearize() const {
  // Steady drilling at the final set-points: the hook force leaves W0 on the bit by the axial balance.
  const double omega = md_.top_speed.knots().back().second;
  const double start_rop = SteadyDrilling(md_, md_.top_speed.Value(0.0)).rop;  // V0, the start's rate of penetration
  HoistBalance balance;
  for (double l : md_.axial.load) balance.buoyant_weight += l;
  for (double c : md_.axial.damping) balance.drag_per_speed += c;  // sum of c_a times piece length
  // The hoist's dashpot pulls against the block paying out at the start's rate V0: at other set-points it carries
  // c_h (V - V0), a drag like the string's with an offset.
  if (md_.hoist_damping > 0) {
    balance.buoyant_weight += md_.hoist_damping * start_rop;
    balance.drag_per_speed += md_.hoist_damping;
  }
  Model at = md_;
  if (md_.rig) {
    // The drawworks pays out at the rate of penetration of the start: steady drilling at omega keeps that rate, and
    // the weight on bit cuts its depth per revolution.
    at.weight_on_bit = md_.ContactForce() + md_.CutWeightPerDepth() * 2 * kPi * start_rop / omega;
  } else if (md_.axial_coupling) {
    at.weight_on_bit = balance.WeightOnBit(md_, omega, md_.hook_force.knots().back().second);
  }
  if (!(omega > 0) || !(at.weight_on_bit > md_.ContactForce())) return {};  // no steady drilling
  const Steady s = SteadyDrilling(at, omega);
  analysis::AxialTorsionalString string{LinearChannel(md_.torsion, md_.top_inertia, md_.bit_inertia),
                                        LinearChannel(md_.axial, md_.hoist_mass, md_.bit_mass, md_.hoist_damping),
                                        md_.pi, md_.CutWeightPerDepth(), md_.CutTorquePerDepthAt(omega),
                                        md_.blades, md_.axial_coupling};
  DescribeTopDrive(md_, string);
  string.rig = md_.rig;
  if (md_.rig && md_.rig->drawworks)  // its supply of steady drilling: the start's pay-out under the steady pull
    string.drawworks_supply_hz = md_.rig->drawworks->SteadySupply(start_rop, md_.hook_force.Value(0.0));
  string.unbalance = md_.unbalance;
  // The steady whirl of an unbalanced BHA costs the bit a torque too.
  const double whirl_drag = md_.unbalance ? md_.unbalance->SteadyDragTorque(omega) : 0.0;
  const double top_torque = SteadyTopTorque(md_.torsion, s.tob + whirl_drag, omega);
  if (md_.law.torque_limit > 0 && top_torque >= md_.law.torque_limit) return {};  // the drive cannot hold the speed
  // The bit torque's slope at the held depth of cut: a Stribeck law's or a contact law's (with eq. 2.33 the cut's too).
  const double friction_slope = at.SteadyTorqueSlope(at.weight_on_bit, omega);
  analysis::NetworkLinearization lin;
  try {
    lin = analysis::LinearizeAxialTorsional(string, {omega, s.rop, friction_slope, top_torque});
  } catch (const std::domain_error&) {  // the induction motor cannot carry the steady torque (beyond pull-out)
    return {};
  } catch (const std::invalid_argument& e) {  // parameters out of the linearization's range (e.g. mutated to 1e-300)
    throw InputError("/model", std::string("no linearization for this model: ") + e.what());
  }
  nlohmann::json point = {{"bit_speed_rad_s", omega},
                          {"weight_on_bit_N", s.wob},
                          {"hook_force_N", md_.hook_force.knots().back().second},
                          {"depth_of_cut_m", s.depth},
                          {"rop_m_h", 3600 * s.rop},
                          {"bit_torque_Nm", s.tob},
                          {"top_torque_Nm", top_torque},
                          {"bit_torque_slope_Nms_per_rad", friction_slope},
                          {"cut_delay_s", 2 * kPi / (md_.blades * omega)},
                          {"axial_coupling", md_.axial_coupling}};
  if (md_.unbalance) {
    point["steady_whirl_radius_m"] = md_.unbalance->WhirlAmplitude(omega);
    point["whirl_drag_torque_Nm"] = whirl_drag;
  }
  if (md_.strength_heterogeneity.on()) point["rock_strength_heterogeneity"] = LinearizedRock(md_);
  return {{std::move(point), std::move(lin.state_names), std::move(lin.system)}};
}

class AxialTorsionalKind : public ModelKind {
 public:
  std::string name() const override { return "axial_torsional"; }
  std::string description() const override {
    return "coupled axial-torsional waves in a pipe with a lumped bit and the Richard-Germay-Detournay bit-rock law "
           "(state-dependent cut delay t_n, set-valued wear-flat contact and friction, lift-off); PI top drive (stiff, "
           "SoftTorque/SoftSpeed, Z-Torque or wave cancellation, with torque limit and actuator delay), hoist under "
           "constant hook force; optional BHA section, Kelvin-Voigt damping, Stribeck bit friction, the chapter's "
           "smooth wear-flat friction functions (rock/contact), DC motor, "
           "BHA mass unbalance (Jeffcott rotor at the bit), two-mass hoisting rig, axial coupling off";
  }
  nlohmann::json FieldSchema() const override {
    nlohmann::json fields = {
        {"string/length_m", "in (0, 20000], top drive to bit"},
        {"string/outer_diameter_m", "> 0"},
        {"string/inner_diameter_m", ">= 0, < outer"},
        {"string/youngs_modulus_Pa", "> 0"},
        {"string/shear_modulus_Pa", "> 0"},
        {"string/density_kg_m3", "> 0, steel"},
        {"string/mud_density_kg_m3", ">= 0, < steel, default 0 (buoyancy only)"},
        {"string/torsional_damping_Nms_per_rad_m", "c_t >= 0, viscous, per metre"},
        {"string/axial_damping_Ns_per_m2", "c_a >= 0, viscous, per metre"},
        {"string/subsections",
         "integer in [2, 400], default 20: the pipe's pieces (damping and weight lumped at "
         "their nodes)"},
        {"string/axial_kelvin_voigt_s", "eta_a in [0, 10] s, default 0: axial N += eta_a E A dv/ds"},
        {"string/bha/length_m",
         "> 0, < string/length_m: drill collars of the same steel between the pipe and "
         "the bit (string/length_m stays top drive to bit). string/bha may also be an "
         "array of such sections, top to bottom (heavy-weight pipe, collars, ...)"},
        {"string/bha/outer_diameter_m", "> 0"},
        {"string/bha/inner_diameter_m", ">= 0, < outer"},
        {"string/bha/subsections", "integer in [1, 400], default: pieces about as long as the pipe's"},
        {"string/bha/torsional_damping_Nms_per_rad_m", ">= 0, default the pipe's"},
        {"string/bha/axial_damping_Ns_per_m2", ">= 0, default the pipe's"},
        {"string/side_friction/torque_per_m_Nm",
         ">= 0: Coulomb friction of the pipe against the borehole "
         "(set-valued: a stopped piece of pipe is held)"},
        {"string/side_friction/from_m", ">= 0, default 0 (measured depth where it starts)"},
        {"string/side_friction/to_m", "> from_m, default: the bit"},
        {"bit/inertia_kgm2", "J_b > 0 (bit, and the BHA unless string/bha distributes it)"},
        {"bit/mass_kg", "M_b > 0"},
        {"axial_coupling",
         "boolean, default true; false: no axial dynamics, weight on bit held at W0 and depth "
         "of cut what W0 cuts in the rock under the bit (the steady one in homogeneous rock)"},
        {"top/type",
         "top_drive (default: the stiff PI speed controller) | soft_torque (the PI tracking the "
         "set-point less the high-passed string torque; kp/ki or tuning_period_s) | z_torque (the same "
         "matched to the pipe's impedance) | wave_cancellation (the top absorbs the arriving torsional "
         "wave exactly and injects a down-going one under a slow speed loop, see "
         "speed_loop_corner_rad_s) | sliding_mode (z_torque's command held by a sliding surface, "
         "see surface_corner_rad_s); the laws drive the top's torque (no motor)"},
        {"top/inertia_kgm2", "J_td > 0"},
        {"top/kp_Nms_per_rad",
         ">= 0; wave_cancellation: > 0, the torque per rad/s that pulls the top onto the "
         "speed absorbing the arriving wave"},
        {"top/ki_Nm_per_rad",
         ">= 0; the run starts, and `stability` linearizes, in steady drilling at the "
         "set-point, which only integral action holds: with 0 (a proportional drive) the "
         "start is out of balance and the drive settles below its set-point"},
        {"top/speed_rad_s", "set-point schedule [rad/s]"},
        {"top/motor/motor_constant_Nm_per_A",
         "K > 0: optional DC motor (absent: the PI output is the torque); "
         "V = R/K u_PI + K Omega_ref, La I' = V - K w_top - R I, torque K I"},
        {"top/motor/resistance_ohm", "R > 0"},
        {"top/motor/inductance_H", "La > 0"},
        {"hoist/mass_kg", "M_td > 0"},
        {"hoist/damping_Ns_per_m",
         "c_h >= 0, default 0: a dashpot from the hoist to the travelling block, which "
         "pays out line at the steady rate of penetration V0 (-c_h (v_top - V0); the "
         "top's reflection of Aarsnes & van de Wouw 2019); not with hoist/rig"},
        {"hoist/hook_force_N",
         "H(t) [N], a number or {\"knots\": [[t, v], ...]}, instead of weight_on_bit_N: the run "
         "starts in steady drilling under H(0), with W0 = (W_b - H(0) + kappa a sigma l) / "
         "(1 + kappa), kappa = c_a L Omega0 / (2 pi a zeta eps), which must exceed a sigma l"},
        {"hoist/weight_on_bit_N",
         "W0 > a sigma l: the hook force is set so that steady drilling has this weight "
         "on bit (H = buoyant weight of pipe, BHA and bit - W0 - c_a L V0)"},
        {"hoist/rig/derrick_mass_kg",
         "M_rg1 > 0: optional two-mass hoisting rig (chapter eq. 2.22), absent: the "
         "hook force; the top drive hangs from the travelling block on a rigid hook, "
         "the drawworks pays out line at the steady rate of penetration; needs "
         "weight_on_bit_N, not with axial_coupling false"},
        {"hoist/rig/block_mass_kg", "M_rg2 > 0: cables, crown and travelling blocks"},
        {"hoist/rig/derrick_damping_Ns_per_m", "gamma_rg1 >= 0"},
        {"hoist/rig/block_damping_Ns_per_m", "gamma_rg2 >= 0"},
        {"hoist/rig/ground_stiffness_N_per_m", "k_rg01 > 0: derrick to ground"},
        {"hoist/rig/cable_stiffness_N_per_m", "k_rg12 > 0: derrick to travelling block"},
        {"hoist/rig/cable_tension_change_N",
         "u_F(t) - u_F0 [N], up on the derrick: a number or {\"knots\": "
         "[[t, v], ...]}, default 0 (u_F0: the tension of steady drilling)"},
        {"hoist/rig/drawworks/line_radius_m",
         "r > 0: optional drawworks (chapter eq. 2.37), an induction motor "
         "through a gear on the drum paying out the line at r times the "
         "drum's speed (the drum's radius over the reeving's lines); absent: "
         "a constant pay-out at the steady rate of penetration"},
        {"hoist/rig/drawworks/inertia_kgm2", "J > 0: drum and motor referred to the drum"},
        {"hoist/rig/drawworks/gear_ratio", "n > 0, default 1: motor turns per drum turn"},
        {"hoist/rig/drawworks/supply_change_Hz",
         "f(t) - f0 [Hz], default 0: a number or {\"knots\": [[t, v], "
         "...]}; f0 the supply that pays out at the steady rate of "
         "penetration under the steady hook force (summary "
         "drawworks_steady_supply_frequency_Hz)"},
        {"gravity_m_s2", "> 0, default 9.81"}};
    fields.update(TopComponentFields("top"));
    const nlohmann::json drawworks_fields = TopComponentFields("hoist/rig/drawworks");  // its machine, as the top's
    for (const auto& [path, text] : drawworks_fields.items())
      if (path.find("/induction_motor/") != std::string::npos) fields[path] = text;
    fields.update(PiTopDriveLawFields("top"));
    fields.update(StringComponentFields("string", "bit"));
    fields["string/kelvin_voigt_s"] = fields["string/kelvin_voigt_s"].get<std::string>() +
                                      "; with side_friction the nodes tied by the dashpots are held by it where it "
                                      "suffices (a convex problem solved exactly)";
    fields.update(RgdFieldSchema());
    fields["top/induction_motor/pole_pairs"] =
        "p, integer in [1, 64]: optional induction motor (absent: the PI output is the torque) on a V/f supply with "
        "slip-frequency control, f = (p n w_m + u_PI / (n G)) / 2 pi at the measured speed w_m, G = p (V/f)^2 / "
        "(4 pi^2 R_r), slip held below R_r / (L_ls + L_lr); not with motor";
    return fields;
  }

  std::unique_ptr<PreparedModel> Prepare(const JsonReader& r) const override {
    Model md;
    const StringSpec string = ReadString(r.Object("string"));
    md.length = string.length;
    md.pipe_damping_per_m = {string.sections[0].c_t, string.sections[0].c_a};
    const JsonReader b = r.Object("bit");
    md.bit_inertia = b.Number("inertia_kgm2", Range::Positive());
    md.bit_mass = b.Number("mass_kg", Range::Positive());
    ReadRgdBit(b, md);
    md.unbalance = ReadUnbalance(b);
    b.Finish();
    ReadRgdRock(r.Object("rock"), md);
    r.RefuseRenamed("top_drive", "/model/top");
    const JsonReader td = r.Object("top");
    const std::string type = td.String("type", PiTopDriveTypes(), "top_drive");
    PiTopDriveSpec drive = ReadPiTopDrive(td, type, TorsionalImpedance(string, string.sections[0]));
    md.top_inertia = drive.inertia;
    md.top_speed = drive.speed;
    if (td.Has("motor")) {
      const JsonReader mo = td.Object("motor");
      md.motor.on = true;
      md.motor.k = mo.Number("motor_constant_Nm_per_A", Range::Positive());
      md.motor.resistance = mo.Number("resistance_ohm", Range::Positive());
      md.motor.inductance = mo.Number("inductance_H", Range::Positive());
      mo.Finish();
    }
    ReadTopMotorAndGear(td, md);
    FinishPiTopDrive(td, type, md.gear, md.TopInertia(), drive);
    md.pi = drive.pi;
    md.law = drive.law;
    CheckTopDriveLaw(td, type, string, md);
    td.Finish();
    if (!(md.top_speed.Value(0.0) > 0))
      throw InputError(td.PathOf("speed_rad_s"), "the run starts in steady drilling: the set-point at t = 0 must be > 0");
    const JsonReader h = r.Object("hoist");
    md.hoist_mass = h.Number("mass_kg", Range::Positive());
    md.hoist_damping = h.Number("damping_Ns_per_m", Range::NonNegative(), 0.0);
    const bool hook_given = h.Has("hook_force_N");
    if (hook_given == h.Has("weight_on_bit_N"))
      throw InputError(h.path(), "expected either weight_on_bit_N (the hook force is set for it) or hook_force_N (a "
                                 "schedule), " + std::string(hook_given ? "not both" : "got neither"));
    if (hook_given) md.hook_force = model::Schedule::FromJson(h.Raw("hook_force_N"), h.PathOf("hook_force_N"));
    else md.weight_on_bit = h.Number("weight_on_bit_N", Range::Positive());
    if (h.Has("rig")) {
      if (hook_given)
        throw InputError(h.PathOf("rig"), "the rig carries the top drive itself: expected weight_on_bit_N (the steady "
                                          "state it keeps) instead of hook_force_N");
      md.rig = ReadHoistRig(h.Object("rig"));
      if (md.hoist_damping > 0)
        throw InputError(h.PathOf("damping_Ns_per_m"), "expected 0 with hoist/rig (the rig's own dampers hold the "
                                                       "block); the dashpot is for the hook-force hoist");
    }
    h.Finish();
    const double g = r.Number("gravity_m_s2", Range::Positive(), 9.81);
    md.axial_coupling = r.Boolean("axial_coupling", true);
    r.Finish();
    if (md.rig && !md.axial_coupling)
      throw InputError(h.PathOf("rig"), "expected no rig with axial_coupling false (no axial dynamics to hang it on)");
    if (!hook_given && !(md.weight_on_bit > md.ContactForce()))
      throw InputError(h.PathOf("weight_on_bit_N"), "expected more than the wear-flat contact force a sigma l = " +
                                                        ReadableNumber(md.ContactForce()) + " N (no cutting otherwise; "
                                                        "a = /model/bit/radius_m, sigma l = /model/rock/sigma_l_N_per_m)");
    if (hook_given && !md.axial_coupling && !md.hook_force.IsConstant())
      throw InputError(h.PathOf("hook_force_N"), "expected a constant with axial_coupling false (no axial dynamics: "
                                                 "the weight on bit stays at H(0)'s steady value)");

    BuildChannels(string, g, md);
    md.axial.load[md.m] += md.bit_mass * g * (1 - string.rho_mud / string.rho);
    const HoistBalance balance = Balance(md, string);
    const double omega0 = md.top_speed.Value(0.0);
    if (!hook_given) {
      md.hook_force = model::Schedule(balance.HookForce(md, omega0, md.weight_on_bit));
    } else {
      md.weight_on_bit = balance.WeightOnBit(md, omega0, md.hook_force.Value(0.0));
      if (!(md.weight_on_bit > md.ContactForce()))
        throw InputError(h.PathOf("hook_force_N"),
                         "the hook force at t = 0, " + ReadableNumber(md.hook_force.Value(0.0)) + " N, leaves " +
                             ReadableNumber(md.weight_on_bit) + " N on the bit in steady drilling (buoyant weight " +
                             ReadableNumber(balance.buoyant_weight) + " N); expected more than the wear-flat contact "
                             "force a sigma l = " + ReadableNumber(md.ContactForce()) + " N");
    }
    if (md.induction_on) {
      try {
        CheckSteadyStart(md);
      } catch (const std::domain_error& e) {
        throw InputError(td.PathOf("induction_motor"), std::string("no steady drilling at the set-point: ") + e.what());
      }
    }
    if (md.rig && md.rig->drawworks) {
      try {
        md.rig->drawworks->SteadySupply(SteadyDrilling(md, md.top_speed.Value(0.0)).rop, md.hook_force.Value(0.0));
      } catch (const std::domain_error& e) {
        throw InputError(h.PathOf("rig") + "/drawworks/induction_motor",
                         std::string("cannot hold the steady hook force while paying out: ") + e.what());
      }
    }
    return std::make_unique<AxialTorsionalModel>(std::move(md));
  }
};

}  // namespace

std::unique_ptr<ModelKind> MakeAxialTorsionalKind() { return std::make_unique<AxialTorsionalKind>(); }

}  // namespace drillwave::cases
