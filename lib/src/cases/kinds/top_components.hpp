#pragma once
// Readers of the top-of-string components that more than one kind offers (chapter §2.5-2.6): the induction motor on
// a V/f supply, the gear between a motor and the top drive (rigid, or compliant: the rig's two-mass model), the PI
// speed controller's gains and the PI top drive with its law against stick-slip (issue 35), with their field
// documentation for `drillwave kinds`.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "drillwave/io/json_reader.hpp"
#include "drillwave/model/gear.hpp"
#include "drillwave/model/induction_motor.hpp"
#include "drillwave/model/pi_controller.hpp"
#include "drillwave/model/schedule.hpp"
#include "drillwave/model/top_drive_law.hpp"

namespace drillwave::cases {

// The machine constants of top/induction_motor (the supply-frequency schedule stays with the top's set-points).
model::InductionMotor ReadInductionMotor(const io::JsonReader& motor);
// top/gear and top/motor_inertia_kgm2 (absent gear: ratio 1, rigid, no motor inertia).
model::Gear ReadGear(const io::JsonReader& top);
// The PI speed controller's gains, each >= 0, under the keys its drive names them (a torque's by default; a DC
// motor's speed loop gives volts).
model::PiController ReadPiController(const io::JsonReader& top, const char* kp_key = "kp_Nms_per_rad",
                                     const char* ki_key = "ki_Nm_per_rad");
// Field documentation of the induction motor and the gear, keyed by their paths below the top block (e.g. "top").
nlohmann::json TopComponentFields(const std::string& top);

// A PI top drive whose output is its torque, with its law (top/type top_drive: the stiff PI; soft_torque: the PI
// tracking the set-point less the high-passed string torque, its gains given or SoftSpeed-tuned; z_torque: the same
// matched to the pipe's impedance; wave_cancellation: the arriving wave absorbed exactly, a wave injected under a slow
// speed loop, model::WaveCancellation), read alike by every kind that has one.
struct PiTopDriveSpec {
  double inertia = 0;  // the top drive's own, kg m^2
  model::Schedule speed;
  model::PiController pi;
  model::TopDriveLaw law;
  double tuning_period_s = 0;  // SoftSpeed: ki is set by FinishPiTopDrive once the lumped inertia is known
};
// The top/type names of a PI top drive with its law against stick-slip, stiff PI first: what every kind with such a
// top accepts, and what compare-controllers compares.
const std::vector<std::string>& PiTopDriveTypes();
bool IsPiTopDriveType(const std::string& type);
// The drive's fields up to its gear, for top/type `type` (IsPiTopDriveType); pipe_impedance is Z = G J / c of the top
// section, the SoftSpeed kp, Z-Torque's default impedance and the wave cancellation's.
PiTopDriveSpec ReadPiTopDrive(const io::JsonReader& top, const std::string& type, double pipe_impedance);
// After the gear: the actuator delay, the torque feedback and the wave cancellation refused behind a compliant gear,
// the SoftSpeed ki from the inertia the top's speed carries (with a rigid gear's motor), the handover's integral gain.
void FinishPiTopDrive(const io::JsonReader& top, const std::string& type, const model::Gear& gear,
                      double lumped_inertia, PiTopDriveSpec& drive);
// A wave-cancelling top reads the wave arriving at it alone: refused, naming top/type, on a string with Kelvin-Voigt
// dashpots (retardation time kelvin_voigt_s > 0), whose pull on the top would be part of what it must absorb.
void CheckWaveCancellationString(const io::JsonReader& top, const model::TopDriveLaw& law, double kelvin_voigt_s);
// Field documentation of the law's fields (torque limit, delay, tuning, feedback, impedance, speed loop corner,
// handover).
nlohmann::json PiTopDriveLawFields(const std::string& top);

}  // namespace drillwave::cases
