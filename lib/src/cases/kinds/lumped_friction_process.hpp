#pragma once
// A chain of n lumped inertias: neighbours coupled by a spring and a damper, each inertia with a damper to ground
// and optionally a friction law, the first inertia driven by a prescribed speed, a PI speed controller or a torque.
// Set-valued laws (Coulomb, Stribeck, humped, asymmetric) give real stick phases: every inertia sticks and slips on
// its own, each transition located as an event (DESIGN.md §2). Shared by the kinds two_mass (chapter eqs. 2.1-2.4)
// and two_disc (setup seed eqs. 1-7), which are chains of two.
//
// The integrated state is (twists phi_j - phi_{j+1}, speeds, angles, PI integral, work in, energy dissipated): the
// twist form of chapter eq. 2.3 and setup eq. 4, plus the angles for the statistics and the two energy integrals,
// so that work in = dissipation + change of stored energy can be checked along the run.
#include <optional>
#include <string>
#include <vector>

#include "drillwave/analysis/periodic_orbits.hpp"
#include "drillwave/bitrock/friction.hpp"
#include "drillwave/cases/model_kind.hpp"
#include "drillwave/cases/statistics.hpp"
#include "drillwave/integration/options.hpp"
#include "drillwave/io/json_reader.hpp"
#include "drillwave/model/pi_controller.hpp"
#include "drillwave/model/schedule.hpp"

namespace drillwave::cases::lumped {

enum class Drive { kPrescribedSpeed, kPiSpeed, kTorque };

// A normal load the friction is proportional to that follows the friction torque T itself (the UFRJ rig's weight on
// bit rises with its torque on bit, wob ~ 388 + 84 tob N, 20 ms behind it): the friction scale s is a state with
//   time_constant_s s' = applied(t) + gain_per_Nm (T - reference_Nm) - s,
// applied(t) the inertia's friction_scale schedule; while stuck T is the torque that holds the inertia. The loop
// through T = s law(w) stays stable while gain_per_Nm times the law's static level is below 1.
struct NormalLoad {
  double gain_per_Nm = 0;      // scale per N m of friction torque, >= 0
  double reference_Nm = 0;     // the torque at which the load is the applied one
  double time_constant_s = 0;  // > 0
};

struct Inertia {
  double inertia_kgm2 = 1;  // > 0
  double damping_Nms_per_rad = 0;  // damper to ground, >= 0
  std::optional<bitrock::FrictionLaw> friction;
  model::Schedule friction_scale{1.0};  // multiplies every torque level of the law (e.g. weight on bit / nominal)
  std::optional<NormalLoad> normal_load;  // with a friction law: the scale follows the torque (above)
};

struct Coupling {
  double stiffness_Nm_per_rad = 1;  // > 0
  double damping_Nms_per_rad = 0;   // >= 0
};

struct Chain {
  std::vector<Inertia> inertias;    // inertias[0] is the driven end
  std::vector<Coupling> couplings;  // couplings[j] joins inertias j and j + 1
  Drive drive = Drive::kTorque;
  model::Schedule setpoint;  // speed [rad/s] (prescribed, PI) or the input of the torque drive
  double torque_gain = 1;    // torque drive: torque = torque_gain * setpoint (e.g. motor constant * voltage)
  model::PiController pi;    // PI drive
  // PI drive: its torque clamped to +-drive_torque_limit_Nm (0: none), the integral held while the clamp acts against
  // the speed error (no wind-up): a motor drive's current limit, which holds a stalled string at a fixed torque.
  double drive_torque_limit_Nm = 0;
  // > 0: every friction law with sign(w) replaced by tanh(w / eps) (a smooth reference model without stick phases).
  double friction_smoothing_rad_s = 0;

  // Throws std::invalid_argument for an inconsistent chain (sizes, a friction law on a prescribed-speed end, ...).
  void Validate() const;
  // The PI drive's torque for its unclamped output, and whether its integral is held there (the clamp acts and the
  // speed error would drive the output further beyond it).
  double ClampedDriveTorque(double output) const;
  bool DriveIntegralHeld(double output, double speed_error) const;
  bool HasNormalLoad() const;
};

// A run sampled at the output interval (or at every step if the interval is <= 0).
struct ChainRun {
  std::vector<double> time_s;
  // Per inertia: speed [rad/s] (0 while stuck), angle [rad], friction torque [N·m] (while stuck: the torque that
  // holds it), 1 while stuck.
  std::vector<std::vector<double>> speed_rad_s, angle_rad, friction_Nm, stuck;
  std::vector<std::vector<double>> coupling_torque_Nm;  // per coupling: k (phi_j - phi_{j+1}) + c (w_j - w_{j+1})
  std::vector<double> drive_torque_Nm;                  // torque the drive puts into inertia 0
  std::vector<std::vector<double>> friction_scale;      // per inertia: the scale of its friction law (the normal load)
  // Work in - dissipated - (stored - stored at start), from the integrated energy states; 0 up to the tolerance.
  std::vector<double> energy_residual_J;
  std::vector<std::vector<StuckInterval>> stuck_intervals;  // per inertia, from the events
  integration::IntegrationStats stats;
  double work_in_J = 0, dissipated_J = 0, stored_change_J = 0;  // at the end of the run
};

ChainRun RunChain(const Chain& chain, const RunSettings& settings);

// What every chain kind reports, with inertia 0 as the "top" and the last inertia as the "bit": the common channels
// (top_rpm, bit_rpm, top_torque_Nm = the first coupling's torque, bit_torque_Nm = the bit's friction, bit_angle_rad,
// bit_stuck, drive_torque_Nm, energy_balance_residual_J), the bit's stick-slip statistics over the window, the
// energy balance and the integrator's counts. Kinds add their own channels and keys.
RunResult ChainResult(const ChainRun& run, const RunSettings& settings);

// Steady states with every inertia turning at one speed w > 0, at the inputs' final values (a prescribed or PI
// speed end fixes w; a torque drive gives every root of drive = sum of friction and damper torques at w), each
// with the linear system of small perturbations: state (twists, speeds of the free inertias, PI integral).
std::vector<LinearizedOperatingPoint> LinearizeChain(const Chain& chain);

// The chain at its inputs' final values as a piecewise-smooth field (state as LinearizeChain's, one mode per
// combination of stick regimes), for periodic orbits and their continuation; its Equilibria() are LinearizeChain's.
std::shared_ptr<const analysis::PiecewiseSmoothField> ChainOrbitField(const Chain& chain);

// The optional field "friction_smoothing_rad_s" of a chain kind: 0 (set-valued laws with stick phases) or a
// smoothing speed of at least kMinFrictionSmoothing_rad_s.
constexpr double kMinFrictionSmoothing_rad_s = 1e-6;
double ReadFrictionSmoothing(const io::JsonReader& model);

}  // namespace drillwave::cases::lumped
