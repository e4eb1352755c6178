// Model kind "torsional_wave": a drill string of uniform sections (pipe, collars) as a d'Alembert wave network,
// with a top boundary from the seeds (imposed speed, dissipative top, top drive with PI control, torque) and a bit
// with any friction law. Distributed viscous damping is lumped into dashpots at internal massless nodes, Kelvin-Voigt
// damping into dashpots across the sub-sections (waves::Section::dashpot). Optional bit/unbalance: the BHA's lateral
// motion as the Jeffcott rotor of the failure seed (eqs. 21-23) at the bit node.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "drillwave/cases/friction_json.hpp"
#include "drillwave/analysis/network_linearization.hpp"
#include "drillwave/analysis/torsional_linearization.hpp"
#include "drillwave/cases/kinds.hpp"
#include "drillwave/cases/statistics.hpp"
#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/waves/network_simulation.hpp"
#include "string_components.hpp"
#include "top_components.hpp"

namespace drillwave::cases {
namespace {

using io::JsonReader;
using Range = io::Range;


waves::Section ReadSection(const JsonReader& r) {
  const double length = r.Number("length_m", Range::Positive());
  const double g = r.Number("shear_modulus_Pa", Range::Positive());
  const double rho = r.Number("density_kg_m3", Range::Positive());
  double j;
  if (r.Has("polar_moment_m4")) {
    j = r.Number("polar_moment_m4", Range::Positive());
  } else {
    const double ro = r.Number("outer_radius_m", Range::Positive());
    const double ri = r.Number("inner_radius_m", Range::Between(0, ro), 0.0);
    if (!(ri < ro)) throw InputError(r.PathOf("inner_radius_m"), "expected a number below outer_radius_m");
    j = 0.5 * kPi * (std::pow(ro, 4) - std::pow(ri, 4));
  }
  r.Allow("name");
  r.Finish();
  const waves::Section s = waves::Section::Torsional(length, g, rho, j);  // extremes overflow: say which section
  if (!(s.travel_time_s > 0 && s.impedance > 0 && std::isfinite(s.travel_time_s) && std::isfinite(s.impedance)))
    throw InputError(r.path(), "travel time " + ReadableNumber(s.travel_time_s) + " s and impedance " +
                                   ReadableNumber(s.impedance) + " N m s must be positive and finite: length_m, "
                                   "shear_modulus_Pa, density_kg_m3 or the polar moment is out of range");
  return s;
}

// Consecutive sections of one pipe (the same impedance and wave speed) as one: their junction reflects nothing and
// transmits the whole wave, so the string is the same, and the engine should not pay for a cut that scatters nothing
// (each junction is a node whose waves are stored, checked and looked up at every step, and a node of the linear
// verdict's characteristic matrix: 16 such parts of saldivar-stickslip cost 100 times the one section, issue 33).
std::vector<waves::Section> JoinSectionsOfOnePipe(const std::vector<waves::Section>& sections) {
  auto same = [](double a, double b) { return std::abs(a - b) <= 1e-12 * std::max(std::abs(a), std::abs(b)); };
  std::vector<waves::Section> joined;
  for (const waves::Section& s : sections) {
    if (!joined.empty() && same(joined.back().impedance, s.impedance) &&
        same(joined.back().wave_speed(), s.wave_speed())) {
      joined.back().length_m += s.length_m;
      joined.back().travel_time_s += s.travel_time_s;
    } else {
      joined.push_back(s);
    }
  }
  return joined;
}

// Splits each section into m equal parts and puts a dashpot gamma * length / m to ground at each internal node:
// the distributed viscous damping of eqs. 2.20/2.24 (gamma per unit length) lumped so the reduction stays exact.
// Kelvin-Voigt damping (T += eta G J dw/ds) is a dashpot eta G J / part length = eta Z / part travel time across
// each part.
void AddSectionsWithDamping(const std::vector<waves::Section>& sections, double gamma_per_m, double kelvin_voigt_s,
                            int subsections, waves::Network& net) {
  for (std::size_t k = 0; k < sections.size(); ++k) {
    const waves::Section& s = sections[k];
    const int m = gamma_per_m > 0 || kelvin_voigt_s > 0 ? subsections : 1;
    for (int part = 0; part < m; ++part) {
      const double tau = s.travel_time_s / m;
      net.sections.push_back({s.length_m / m, tau, s.impedance, kelvin_voigt_s * s.impedance / tau});
      const bool last = k + 1 == sections.size() && part + 1 == m;
      if (last) break;
      waves::Node node;
      node.name = part + 1 == m ? "junction" : "damper";
      // Each internal node carries the damping of one part length; both string ends take half a part.
      node.ground_damping = gamma_per_m * s.length_m / m;
      net.nodes.push_back(node);
    }
  }
}

// The string as the continuum its Kelvin-Voigt parts discretize (analysis/kelvin_voigt_continuum.hpp), for the tops
// that close it (imposed speed, dashpot, a PI speed drive without torque feedback, actuator delay, handover or
// compliant gear) and a bit without lateral BHA; the ends' own dampers, without the half parts of lumped viscous
// damping. The bit's torque slope is set per operating point.
std::optional<analysis::KelvinVoigtString> ContinuumString(const std::vector<waves::Section>& sections, double gamma,
                                                           double eta, const waves::Node& top, const waves::Node& bit) {
  if (!(eta > 0) || bit.lateral) return std::nullopt;
  analysis::KelvinVoigtString out;
  for (const waves::Section& s : sections) out.sections.push_back({s.travel_time_s, s.impedance, s.length_m});
  out.kelvin_voigt_s = eta;
  out.viscous_damping_Nms_per_rad_m = gamma;
  out.bit_inertia_kgm2 = bit.LumpedInertia();
  using Kind = analysis::ContinuumTop::Kind;
  switch (top.drive) {
    case waves::Drive::kPrescribedSpeed: out.top = {Kind::kImposedSpeed, 0, 0, 0}; return out;
    case waves::Drive::kSpeedDashpot:
      out.top = {Kind::kDashpot, top.drive_damping + top.ground_damping, 0, 0};
      return out;
    case waves::Drive::kPiSpeedController:
      if (top.has_torque_feedback() || top.law.actuator_delay_s > 0 || top.law.handover.active() ||
          top.has_compliant_gear())
        return std::nullopt;
      out.top = {Kind::kPiSpeed, top.ground_damping + top.pi.kp, top.LumpedInertia(), top.pi.ki};
      return out;
    default: return std::nullopt;
  }
}

// How a motor top is commanded: open loop by a schedule (`open_loop_key`), or by a PI speed controller on speed_rad_s.
struct MotorCommand {
  const char* motor;  // "a DC motor", for messages
  const char* open_loop_key;
  waves::Drive open_loop, speed_controlled;
  const char* kp_key;
  const char* ki_key;
};
void ReadMotorCommand(const JsonReader& r, const MotorCommand& c, waves::Node& top) {
  if (r.Has(c.open_loop_key)) {
    if (r.Has("speed_rad_s"))
      throw InputError(r.PathOf("speed_rad_s"), std::string(c.motor) + " top takes either " + c.open_loop_key +
                                                    " (open loop) or speed_rad_s (speed controller), not both");
    top.drive = c.open_loop;
    top.setpoint = model::Schedule::FromJson(r.Raw(c.open_loop_key), r.PathOf(c.open_loop_key));
  } else {
    top.drive = c.speed_controlled;
    top.pi = ReadPiController(r, c.kp_key, c.ki_key);
    top.setpoint = model::Schedule::FromJson(r.Raw("speed_rad_s"), r.PathOf("speed_rad_s"));
  }
}

// Every top/type of the kind: the PI top drives with their laws and the other ends.
std::vector<std::string> TopTypes() {
  std::vector<std::string> types = {"prescribed_speed", "dissipative"};
  types.insert(types.end(), PiTopDriveTypes().begin(), PiTopDriveTypes().end());
  types.insert(types.end(), {"torque", "dc_motor", "induction_motor"});
  return types;
}

waves::Node ReadTop(const JsonReader& r, const waves::Section& top_section) {
  waves::Node top;
  top.name = "top";
  const std::string type = r.String("type", TopTypes());
  std::optional<PiTopDriveSpec> pi_top;  // PiTopDriveTypes (top_components.hpp)
  if (type == "prescribed_speed") {
    top.drive = waves::Drive::kPrescribedSpeed;
    top.setpoint = model::Schedule::FromJson(r.Raw("speed_rad_s"), r.PathOf("speed_rad_s"));
  } else if (type == "dissipative") {
    top.drive = waves::Drive::kSpeedDashpot;
    top.drive_damping = r.Number("beta_Nms_per_rad", Range::Positive());
    top.setpoint = model::Schedule::FromJson(r.Raw("speed_rad_s"), r.PathOf("speed_rad_s"));
  } else if (IsPiTopDriveType(type)) {
    pi_top = ReadPiTopDrive(r, type, top_section.impedance);
    top.drive = waves::Drive::kPiSpeedController;
    top.inertia = pi_top->inertia;
    top.setpoint = pi_top->speed;
  } else if (type == "dc_motor") {
    top.inertia = r.Number("inertia_kgm2", Range::Positive());
    for (const char* moved : {"motor_constant_Nm_per_A", "resistance_ohm", "inductance_H"})
      r.RefuseRenamed(moved, r.PathOf("motor/") + moved);
    const JsonReader motor = r.Object("motor");
    top.motor.motor_constant = motor.Number("motor_constant_Nm_per_A", Range::Positive());
    top.motor.armature_resistance = motor.Number("resistance_ohm", Range::Positive());
    top.motor.armature_inductance = motor.Number("inductance_H", Range::Positive());
    motor.Finish();
    top.motor.voltage_limit = r.Number("voltage_limit_V", Range::NonNegative(), 0.0);
    ReadMotorCommand(r, {"a DC motor", "voltage_V", waves::Drive::kDcMotorVoltage, waves::Drive::kDcMotorSpeed,
                         "kp_V_s_per_rad", "ki_V_per_rad"}, top);
  } else if (type == "induction_motor") {
    top.inertia = r.Number("inertia_kgm2", Range::Positive());
    top.induction = ReadInductionMotor(r.Object("induction_motor"));
    ReadMotorCommand(r, {"an induction motor", "supply_frequency_Hz", waves::Drive::kInductionMotor,
                         waves::Drive::kInductionMotorSpeed, "kp_Nms_per_rad", "ki_Nm_per_rad"}, top);
  } else {
    top.drive = waves::Drive::kTorque;
    top.inertia = r.Number("inertia_kgm2", Range::NonNegative(), 0.0);  // 0: a force-controlled end (eq. 2.9)
    top.setpoint = model::Schedule::FromJson(r.Raw("torque_Nm"), r.PathOf("torque_Nm"));
  }
  top.ground_damping = r.Number("damping_Nms_per_rad", Range::NonNegative(), 0.0);
  for (const char* key : {"gear", "motor_inertia_kgm2"})
    if (r.Has(key) && (top.massless() || top.drive == waves::Drive::kTorque))
      throw InputError(r.PathOf(key),
                       "a gear and a motor inertia belong to a motor drive: expected top/type top_drive, "
                       "soft_torque, z_torque, wave_cancellation, sliding_mode, dc_motor or induction_motor, got " +
                           type);
  top.gear = ReadGear(r);
  if (pi_top) {
    FinishPiTopDrive(r, type, top.gear, top.LumpedInertia(), *pi_top);
    top.pi = pi_top->pi;
    top.law = pi_top->law;
  }
  r.Finish();
  return top;
}

class TorsionalWaveModel : public PreparedModel {
 public:
  TorsionalWaveModel(waves::Network net, std::optional<analysis::KelvinVoigtString> continuum,
                     double bit_lumped_damping)
      : net_(std::move(net)), continuum_(std::move(continuum)), bit_lumped_damping_(bit_lumped_damping) {}

  RunResult Run(const RunSettings& settings) const override {
    waves::NetworkRunOptions options;
    options.t_end_s = settings.duration_s;
    options.output_interval_s = settings.output_interval_s;
    options.integrator = settings.integrator;
    waves::NetworkRun run = waves::SimulateNetwork(net_, options);
    waves::NetworkTrajectory& tr = run.trajectory;

    // Stuck intervals of the bit from its regime changes.
    const int bit = static_cast<int>(net_.nodes.size()) - 1;
    std::vector<StuckInterval> stuck;
    if (!tr.bit_stuck.empty() && tr.bit_stuck.front() > 0) stuck.push_back({0.0, std::numeric_limits<double>::infinity()});
    for (const waves::RegimeChange& c : run.regime_changes) {
      if (c.node != bit) continue;
      if (c.to == bitrock::Turn::kStuck && c.from != bitrock::Turn::kStuck)
        stuck.push_back({c.time_s, std::numeric_limits<double>::infinity()});
      else if (c.from == bitrock::Turn::kStuck && c.to != bitrock::Turn::kStuck && !stuck.empty())
        stuck.back().end_s = c.time_s;
    }
    RunResult result;
    result.summary = ComputeStickSlipStatistics(stuck, tr.time_s, tr.bit_speed_rad_s, tr.bit_angle_rad,
                                                settings.window_begin_s, settings.window_end_s)
                         .ToJson();
    result.summary["steps"] = run.stats.steps;
    result.summary["events"] = run.stats.events;
    result.summary["breakpoints"] = run.stats.breakpoints;
    result.summary["history_rejections"] = run.stats.history_rejections;
    result.summary["derivative_evaluations"] = run.stats.derivative_evaluations;
    result.summary["integration_wall_time_s"] = run.stats.wall_time_s;

    // The sampled signals are moved into the channels, not copied (long runs sample millions of points).
    result.channels.reserve(9);
    result.channels.push_back({"top_rpm", ToRpm(tr.top_speed_rad_s)});
    result.channels.push_back({"bit_rpm", ToRpm(tr.bit_speed_rad_s)});
    result.channels.push_back({"top_torque_Nm", std::move(tr.top_torque_nm)});
    result.channels.push_back({"bit_torque_Nm", std::move(tr.bit_torque_nm)});
    result.channels.push_back({"bit_angle_rad", std::move(tr.bit_angle_rad)});
    result.channels.push_back({"bit_stuck", std::move(tr.bit_stuck)});
    result.plot_panels = {{"top_rpm", "bit_rpm"}, {"top_torque_Nm", "bit_torque_Nm"}};
    if (!tr.top_current_a.empty()) {
      result.channels.push_back({"top_current_A", std::move(tr.top_current_a)});
      result.plot_panels.push_back({"top_current_A"});
    }
    if (!tr.motor_speed_rad_s.empty()) {  // a motor behind a compliant gear
      result.channels.push_back({"motor_rpm", ToRpm(tr.motor_speed_rad_s)});
      result.channels.push_back({"gear_torque_Nm", std::move(tr.gear_torque_nm)});
      result.plot_panels.push_back({"gear_torque_Nm", "top_torque_Nm"});
    }
    if (const auto& lateral = net_.bit().lateral) {
      // Whirl radius over the window, and the closed form at the window's mean bit speed.
      double sum = 0, largest = 0;
      int n = 0;
      for (std::size_t i = 0; i < tr.time_s.size(); ++i)
        if (tr.time_s[i] >= settings.window_begin_s && tr.time_s[i] <= settings.window_end_s)
          sum += tr.lateral_displacement_m[i], largest = std::max(largest, tr.lateral_displacement_m[i]), ++n;
      result.summary["whirl_amplitude_mean_m"] = n ? sum / n : 0.0;
      result.summary["whirl_amplitude_max_m"] = largest;
      result.summary["steady_whirl_amplitude_m"] =
          lateral->WhirlAmplitude(result.summary["bit_speed_mean_rad_s"].get<double>());
      result.summary["lateral_natural_frequency_rad_s"] = lateral->NaturalFrequency();
      result.channels.push_back({"lateral_displacement_m", std::move(tr.lateral_displacement_m)});
      result.plot_panels.push_back({"lateral_displacement_m"});
    }
    result.time_s = std::move(tr.time_s);
    return result;
  }

  // Steady rotation at the final top set-point. A one-section string with a dissipative top and a bit inertia takes
  // the chapter's scalar neutral DDE (DESIGN.md §1); every other string the wave network's linearization
  // (analysis/network_linearization.hpp), whose roots are the same where both apply.
  std::vector<LinearizedOperatingPoint> Linearize() const override {
    bool scalar_form = true;
    try {
      analysis::CheckLinearizable(net_);
    } catch (const std::invalid_argument&) {
      scalar_form = false;
    }
    return scalar_form ? LinearizeScalar() : LinearizeNetwork();
  }

 private:
  std::vector<LinearizedOperatingPoint> LinearizeScalar() const {
    const double omega = net_.top().setpoint.knots().back().second;
    // The chapter's neutral form (DESIGN.md §1): z'' - Y z''(t - 2 tau) = -Psi z' - Y Psi z'(t - 2 tau)
    // + Pi Omega(t - tau) - [T(z') - Y T(z'(t - 2 tau))] / I_B, with the top's own ground damping in beta.
    const double z = net_.sections.front().impedance, beta = net_.top().drive_damping + net_.top().ground_damping;
    const double inertia = net_.bit().inertia;
    const nlohmann::json ndde = {{"upsilon", (beta - z) / (beta + z)},
                                 {"psi_per_s", z / inertia},
                                 {"pi_per_s", 2 * z * net_.top().drive_damping / (inertia * (beta + z))},
                                 {"round_trip_s", 2 * net_.sections.front().travel_time_s},
                                 {"impedance_Nms_per_rad", z}};
    std::vector<LinearizedOperatingPoint> points;
    for (const analysis::TorsionalOperatingPoint& p : analysis::SteadySlidingStates(net_, omega))
      points.push_back({{{"top_speed_rad_s", p.top_speed_rad_s},
                         {"bit_speed_rad_s", p.bit_speed_rad_s},
                         {"bit_torque_Nm", p.bit_torque_Nm},
                         {"bit_torque_slope_Nms_per_rad", p.torque_slope_Nms_per_rad},
                         {"neutral_dde", ndde}},
                        {"bit_speed_rad_s"},
                        analysis::LinearizeTorsionalString(net_, p)});
    return points;
  }

  // The continuum at the operating point: the bit's slope is the network's less the half part of lumped viscous damping
  // its node carries.
  std::optional<analysis::KelvinVoigtString> ContinuumAt(const analysis::NetworkOperatingPoint& p) const {
    if (!continuum_) return std::nullopt;
    analysis::KelvinVoigtString out = *continuum_;
    out.bit_torque_slope_Nms_per_rad = p.bit_torque_slope_Nms_per_rad - bit_lumped_damping_;
    return out;
  }

  std::vector<LinearizedOperatingPoint> LinearizeNetwork() const {
    std::vector<LinearizedOperatingPoint> points;
    std::vector<analysis::NetworkOperatingPoint> steady;
    try {
      steady = analysis::NetworkSteadyStates(net_);
    } catch (const std::invalid_argument& e) {
      throw InputError("/model", std::string("no linearization for this string: ") + e.what());
    }
    for (const analysis::NetworkOperatingPoint& p : steady) {
      nlohmann::json values = {{"top_setpoint", p.top_setpoint},
                               {"bit_speed_rad_s", p.speed_rad_s},
                               {"top_torque_Nm", p.top_torque_Nm},
                               {"bit_torque_Nm", p.bit_torque_Nm},
                               {"bit_torque_slope_Nms_per_rad", p.bit_torque_slope_Nms_per_rad},
                               {"sections", net_.sections.size()}};
      if (const auto& lateral = net_.bit().lateral) {
        values["steady_whirl_radius_m"] = lateral->WhirlAmplitude(p.speed_rad_s);
        values["whirl_drag_torque_Nm"] = lateral->SteadyDragTorque(p.speed_rad_s);
      }
      analysis::NetworkLinearization lin;
      try {
        lin = analysis::LinearizeNetwork(net_, p);
      } catch (const std::invalid_argument& e) {
        throw InputError("/model", std::string("no linearization for this string: ") + e.what());
      }
      points.push_back({std::move(values), std::move(lin.state_names), std::move(lin.system), ContinuumAt(p)});
    }
    return points;
  }

  waves::Network net_;
  std::optional<analysis::KelvinVoigtString> continuum_;  // bit torque slope 0: the operating point's comes in
  double bit_lumped_damping_;  // the bit's half part of lumped viscous damping (the continuum carries it distributed)
};

class TorsionalWaveKind : public ModelKind {
 public:
  std::string name() const override { return "torsional_wave"; }
  std::string description() const override {
    return "torsional d'Alembert wave network: sections, top boundary, bit with friction (DESIGN.md §1–3); optional "
           "viscous and Kelvin-Voigt damping, BHA mass unbalance (Jeffcott rotor at the bit)";
  }
  nlohmann::json FieldSchema() const override {
    nlohmann::json fields = {
        {"string/sections/*/length_m", "section length [m], > 0 (1 to 100 sections)"},
        {"string/sections/*/shear_modulus_Pa", "G [Pa], > 0"},
        {"string/sections/*/density_kg_m3", "rho [kg/m^3], > 0"},
        {"string/sections/*/polar_moment_m4", "J [m^4], > 0 (or outer_radius_m and inner_radius_m)"},
        {"string/sections/*/name",
         "optional label (consecutive sections of the same impedance and wave speed are "
         "joined into one: their junction scatters nothing)"},
        {"string/torsional_damping_Nms_per_rad_m",
         "distributed viscous damping gamma [N·m·s/rad per m], >= 0, default 0"},
        {"string/damping_subsections",
         "parts per section for the viscous and Kelvin-Voigt damping, 1..1000, "
         "default 20"},
        {"top/type",
         "prescribed_speed | dissipative | top_drive | soft_torque | z_torque | wave_cancellation | sliding_mode "
         "| torque "
         "| dc_motor | induction_motor (wave_cancellation: the top absorbs the arriving torsional wave "
         "exactly and injects a down-going one under a slow speed loop, see speed_loop_corner_rad_s)"},
        {"top/motor/motor_constant_Nm_per_A", "dc_motor (chapter eq. 2.15): k_T = k_e [N·m/A], > 0"},
        {"top/motor/resistance_ohm", "dc_motor: armature resistance R [ohm], > 0"},
        {"top/motor/inductance_H", "dc_motor: armature inductance L [H], > 0"},
        {"top/voltage_limit_V", "dc_motor: armature voltage limit [V], >= 0, default 0 = unlimited"},
        {"top/voltage_V", "dc_motor, open loop: armature voltage schedule [V] (instead of speed_rad_s)"},
        {"top/kp_V_s_per_rad", "dc_motor with speed_rad_s: proportional gain of the speed controller, >= 0"},
        {"top/ki_V_per_rad", "dc_motor with speed_rad_s: integral gain of the speed controller, >= 0"},
        {"top/speed_rad_s", "set-point [rad/s]: a number or {\"knots\": [[t, v], ...]}"},
        {"top/beta_Nms_per_rad", "dissipative top: beta > 0"},
        {"top/inertia_kgm2",
         "top_drive, soft_torque, z_torque, wave_cancellation, sliding_mode, dc_motor, induction_motor: inertia "
         "> 0; torque: >= 0, default 0 (force-controlled end)"},
        {"top/kp_Nms_per_rad",
         "top_drive, soft_torque, z_torque, induction_motor with speed_rad_s: proportional "
         "gain >= 0 (the induction motor's PI gives a torque demand u to its V/f drive: "
         "f = (p n w + u / (n G)) / 2 pi at the measured speed w, G = p (V/f)^2 / (4 pi^2 R_r), "
         "slip held below pull-out); wave_cancellation: > 0, the torque per rad/s that pulls the "
         "top onto the speed absorbing the arriving wave (kp / J: how fast)"},
        {"top/ki_Nm_per_rad",
         "top_drive, soft_torque, z_torque, induction_motor with speed_rad_s: integral gain "
         ">= 0"},
        {"top/torque_Nm", "torque top: schedule [N·m]"},
        {"top/damping_Nms_per_rad", "local damper at the top, >= 0, default 0"},
        {"bit/inertia_kgm2", "bit (BHA) inertia, >= 0 (0: massless bit, smooth friction only)"},
        {"bit/damping_Nms_per_rad", "local damper at the bit, >= 0, default 0"},
        {"bit/friction", "friction law, see below (optional: free bit)"},
        {"initial/bit_speed_rad_s", "rigid rotation at start, default 0 (at rest; a set-valued bit starts stuck)"},
        {"friction laws", FrictionLawSchema()},
    };
    fields.update(TopComponentFields("top"));
    fields.update(PiTopDriveLawFields("top"));
    fields.update(StringComponentFields("string", "bit"));
    fields["string/kelvin_voigt_s"] = fields["string/kelvin_voigt_s"].get<std::string>() +
                                      " (string/damping_subsections parts per section); with a massless bit its "
                                      "smooth friction closes the dashpots' node system";
    fields["bit/unbalance/lateral_mass_kg"] = fields["bit/unbalance/lateral_mass_kg"].get<std::string>() +
                                              "; needs bit/inertia_kgm2 > 0";
    fields["top/supply_frequency_Hz"] = "induction_motor, open loop: supply frequency schedule [Hz] (instead of "
                                        "speed_rad_s); V/f: line voltage volts_per_hertz f, up to voltage_limit_V";
    return fields;
  }

  std::unique_ptr<PreparedModel> Prepare(const JsonReader& model) const override {
    const JsonReader string = model.Object("string");
    std::vector<waves::Section> sections;
    for (const JsonReader& s : string.ObjectArray("sections")) sections.push_back(ReadSection(s));
    if (sections.empty()) throw InputError(string.PathOf("sections"), "expected at least one section");
    // A drill string is made of tens of sections (pipe, heavy-weight, collars, the BHA's parts); each junction splits
    // every wave that reaches it, and the run follows the echoes: 100 equal sections of one pipe cost 71 s for 80 s
    // simulated, 20 000 would run for hours (issue 38).
    constexpr std::size_t kMaxSections = 100;
    if (sections.size() > kMaxSections)
      throw InputError(string.PathOf("sections"), std::to_string(sections.size()) + " sections; expected at most " +
                                                      std::to_string(kMaxSections) +
                                                      " (join sections of the same pipe into one)");
    sections = JoinSectionsOfOnePipe(sections);
    string.RefuseRenamed("viscous_damping_Nms_per_rad_m", string.PathOf("torsional_damping_Nms_per_rad_m"));
    const double gamma = string.Number("torsional_damping_Nms_per_rad_m", Range::NonNegative(), 0.0);
    const double eta = ReadKelvinVoigt(string);
    const int subsections = string.Integer("damping_subsections", 1, 1000, 20);
    string.Finish();

    waves::Network net;
    const JsonReader top = model.Object("top");
    net.nodes.push_back(ReadTop(top, sections.front()));
    CheckWaveCancellationString(top, net.top().law, eta);
    AddSectionsWithDamping(sections, gamma, eta, subsections, net);
    for (const waves::Section& part : net.sections)  // extremes overflow: say which field
      if (!std::isfinite(part.dashpot))
        throw InputError(string.PathOf("kelvin_voigt_s"), "the dashpot eta Z / tau of a part is " +
                                                              ReadableNumber(part.dashpot) + " N m s: expected a "
                                                              "smaller retardation time or fewer damping_subsections");

    const JsonReader bit_reader = model.Object("bit");
    waves::Node bit;
    bit.name = "bit";
    bit.inertia = bit_reader.Number("inertia_kgm2", Range::NonNegative());
    bit.ground_damping = bit_reader.Number("damping_Nms_per_rad", Range::NonNegative(), 0.0);
    if (bit_reader.Has("friction"))
      bit.friction = ReadFrictionLaw(bit_reader.Raw("friction"), bit_reader.PathOf("friction"));
    if (bit.has_set_valued_friction() && bit.massless())
      throw InputError(bit_reader.PathOf("inertia_kgm2"), "a set-valued friction law needs a bit inertia > 0");
    bit.lateral = ReadUnbalance(bit_reader);
    if (bit.lateral && bit.massless())
      throw InputError(bit_reader.PathOf("inertia_kgm2"), "a BHA unbalance (bit/unbalance) needs a bit inertia > 0");
    bit_reader.Finish();
    net.nodes.push_back(bit);
    std::optional<analysis::KelvinVoigtString> continuum = ContinuumString(sections, gamma, eta, net.top(), bit);
    // Half a damping part at each end of the string, so the total equals gamma * length.
    const double top_half_part = 0.5 * gamma * sections.front().length_m / subsections;
    const double bit_half_part = 0.5 * gamma * sections.back().length_m / subsections;
    net.nodes.front().ground_damping += top_half_part;
    net.nodes.back().ground_damping += bit_half_part;

    if (model.Has("initial")) {
      const JsonReader initial = model.Object("initial");
      net.initial.speed_rad_s = initial.Number("bit_speed_rad_s", Range::Any(), 0.0);
      initial.Finish();
    }
    model.Finish();
    try {
      net.Validate();
    } catch (const std::invalid_argument& e) {
      throw InputError(model.PathOf("top"), e.what());
    }
    return std::make_unique<TorsionalWaveModel>(std::move(net), std::move(continuum), bit_half_part);
  }
};

}  // namespace

std::unique_ptr<ModelKind> MakeTorsionalWaveKind() { return std::make_unique<TorsionalWaveKind>(); }

}  // namespace drillwave::cases
