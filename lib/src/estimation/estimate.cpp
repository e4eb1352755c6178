#include "drillwave/cases/friction_json.hpp"
#include "drillwave/estimation/estimate.hpp"

#include <algorithm>
#include <cmath>

#include "drillwave/core/constants.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/validity.hpp"
#include "drillwave/recordings/signals.hpp"
#include "drillwave/estimation/smoothing.hpp"
#include "drillwave/estimation/hybrid_observer.hpp"
#include "drillwave/estimation/lumped_observer.hpp"
#include "drillwave/estimation/wave_string_estimator.hpp"

namespace drillwave::estimation {
namespace {

using nlohmann::json;

double Number(const json& object, const char* key, double fallback) {
  const auto it = object.find(key);
  return it != object.end() && it->is_number() ? it->get<double>() : fallback;
}

LumpedModel LumpedFromCase(const json& model) {
  LumpedModel m;
  const json& top = model.at("top");
  const json& shaft = model.at("string");
  const json& bit = model.at("bit");
  m.top_inertia_kgm2 = top.at("inertia_kgm2").get<double>();
  m.top_damping_Nms_per_rad = Number(top, "damping_Nms_per_rad", 0);
  m.shaft_stiffness_Nm_per_rad = shaft.at("stiffness_Nm_per_rad").get<double>();
  m.shaft_damping_Nms_per_rad = Number(shaft, "damping_Nms_per_rad", 0);
  m.bit_inertia_kgm2 = bit.at("inertia_kgm2").get<double>();
  m.bit_damping_Nms_per_rad = Number(bit, "damping_Nms_per_rad", 0);
  const std::string type = top.at("type").get<std::string>();
  if (type == "torque") {
    m.drive = LumpedModel::Drive::kTorque;
    m.setpoint = model::Schedule::FromJson(top.at("torque_Nm"), "/model/top/torque_Nm");
  } else {
    m.drive = type == "top_drive" ? LumpedModel::Drive::kPiSpeed : LumpedModel::Drive::kPrescribedSpeed;
    m.setpoint = model::Schedule::FromJson(top.at("speed_rad_s"), "/model/top/speed_rad_s");
    m.kp = Number(top, "kp_Nms_per_rad", 0);
    m.ki = Number(top, "ki_Nm_per_rad", 0);
  }
  const double nominal = Number(bit, "nominal_weight_on_bit_N", 1.0);
  double weight = nominal;
  if (bit.contains("weight_on_bit_N")) {
    const model::Schedule w = model::Schedule::FromJson(bit.at("weight_on_bit_N"), "/model/bit/weight_on_bit_N");
    if (!w.IsConstant())
      throw InputError("/model/bit/weight_on_bit_N", "the estimator takes a constant weight on bit (the pendulum has "
                                                      "no axial motion to estimate it from); got a schedule");
    weight = w.Value(0);
  }
  m.weight_on_bit_N = bit.contains("nominal_weight_on_bit_N") || bit.contains("weight_on_bit_N") ? weight : 0.0;
  if (!bit.contains("friction"))
    throw InputError("/model/bit/friction", "the estimator needs the bit's friction law (the case has none)");
  const bitrock::FrictionLaw law = cases::ReadFrictionLaw(bit.at("friction"), "/model/bit/friction");
  m.friction = weight > 0 ? law.Scaled(weight / nominal) : law;
  return m;
}

WaveSection Section(const json& s, double length, double outer, double inner, double c_t, double c_a, int pieces,
                    double g_mod, double e_mod, double rho) {
  WaveSection w;
  w.length_m = length;
  const double polar = kPi / 32 * (std::pow(outer, 4) - std::pow(inner, 4));
  const double area = kPi / 4 * (outer * outer - inner * inner);
  w.torsional_impedance = polar * std::sqrt(g_mod * rho);
  w.torsional_speed_m_s = std::sqrt(g_mod / rho);
  w.axial_impedance = area * std::sqrt(e_mod * rho);
  w.axial_speed_m_s = std::sqrt(e_mod / rho);
  w.torsional_damping_per_m = Number(s, "torsional_damping_Nms_per_rad_m", c_t);
  w.axial_damping_per_m = Number(s, "axial_damping_Ns_per_m2", c_a);
  w.subsections = pieces;
  return w;
}

WaveStringModel WaveFromCase(const json& model, double hook_force_N) {
  WaveStringModel m;
  const json& s = model.at("string");
  const double g_mod = s.at("shear_modulus_Pa").get<double>(), e_mod = s.at("youngs_modulus_Pa").get<double>();
  const double rho = s.at("density_kg_m3").get<double>();
  const double c_t = s.at("torsional_damping_Nms_per_rad_m").get<double>();
  const double c_a = s.at("axial_damping_Ns_per_m2").get<double>();
  const double length = s.at("length_m").get<double>();
  const int pieces = static_cast<int>(Number(s, "subsections", 20));
  std::vector<json> bha;
  if (s.contains("bha")) bha = s.at("bha").is_array() ? s.at("bha").get<std::vector<json>>() : std::vector<json>{s.at("bha")};
  double below = 0;
  for (const json& b : bha) below += b.at("length_m").get<double>();
  const double pipe_length = length - below;
  m.sections.push_back(Section(s, pipe_length, s.at("outer_diameter_m").get<double>(),
                               s.at("inner_diameter_m").get<double>(), c_t, c_a, pieces, g_mod, e_mod, rho));
  for (const json& b : bha) {
    const double l = b.at("length_m").get<double>();
    const int default_pieces = std::clamp(static_cast<int>(std::lround(l / (pipe_length / pieces))), 1, 400);
    m.sections.push_back(Section(b, l, b.at("outer_diameter_m").get<double>(), b.at("inner_diameter_m").get<double>(),
                                 c_t, c_a, static_cast<int>(Number(b, "subsections", default_pieces)), g_mod, e_mod,
                                 rho));
  }
  const json& top = model.at("top");
  m.top_inertia_kgm2 = Number(top, "inertia_kgm2", 0);
  m.top_kp = top.contains("motor") ? 0.0 : Number(top, "kp_Nms_per_rad", 0);  // a motor's loop gives volts
  const json& bit = model.at("bit");
  m.bit_inertia_kgm2 = bit.at("inertia_kgm2").get<double>();
  m.bit_mass_kg = bit.at("mass_kg").get<double>();
  const json& hoist = model.at("hoist");
  m.hoist_mass_kg = Number(hoist, "mass_kg", 0);
  m.weight_on_bit_N = Number(hoist, "weight_on_bit_N", 0);
  m.hook_force_N = hook_force_N;
  return m;
}

}  // namespace

EstimatorModel EstimatorModelFromCase(const json& doc, double hook_force_N) {
  const json& model = doc.at("model");
  EstimatorModel m;
  m.kind = model.at("kind").get<std::string>();
  if (m.kind == "two_mass") {
    m.lumped = LumpedFromCase(model);
  } else if (m.kind == "axial_torsional") {
    m.wave = WaveFromCase(model, hook_force_N);
  } else {
    throw InputError("/model/kind", "'" + m.kind + "': the estimator takes the kinds two_mass (top speed alone, a "
                                                    "Kalman filter) and axial_torsional (top speed and torque, the "
                                                    "waves continued down)");
  }
  return m;
}

bool EstimateOptions::IsValid(std::string* error) const {
  return FractionField(error, "stuck_fraction", stuck_fraction) &&
         FiniteField(error, "stuck_threshold_rad_s", stuck_threshold_rad_s) &&
         FiniteField(error, "smoothing_lag_s", smoothing_lag_s) &&
         FiniteField(error, "model_time_offset_s", model_time_offset_s);
}

BitEstimate EstimateBit(const EstimatorModel& model, const SurfaceSignals& signals, const EstimateOptions& options) {
  ThrowIfInvalid(options);
  if (signals.top_speed_rad_s.size() != signals.time_s.size() || signals.time_s.size() < 8)
    throw ParameterError("from", "the estimator needs the top speed at every sample of the recording (8 at least)");
  // Stuck: |bit speed| below a fraction of the nominal speed, the median top speed (the set-point may be a droop
  // drive's no-load speed, far from the speed it turns at).
  const double threshold = options.stuck_threshold_rad_s > 0
                               ? options.stuck_threshold_rad_s
                               : options.stuck_fraction * MedianAbs(signals.top_speed_rad_s);
  BitEstimate e;
  if (model.kind == "two_mass" && HasInvertibleDrive(model.lumped)) {
    HybridObserverOptions o;
    o.model_time_offset_s = options.model_time_offset_s;
    e = EstimateHybrid(model.lumped, signals, threshold, o);
  } else if (model.kind == "two_mass") {
    LumpedObserverOptions o;
    o.smoothing_lag_s = options.smoothing_lag_s;
    o.model_time_offset_s = options.model_time_offset_s;
    e = EstimateLumped(model.lumped, signals, threshold, o);
  } else {
    e = EstimateWaveString(model.wave, signals, threshold);
  }
  return e;
}

}  // namespace drillwave::estimation
