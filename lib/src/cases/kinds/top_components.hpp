#pragma once
// Readers of the top-of-string components that more than one kind offers (chapter §2.5-2.6): the induction motor on
// a V/f supply, the gear between a motor and the top drive (rigid, or compliant: the rig's two-mass model) and the PI
// speed controller's gains, with their field documentation for `drillwave kinds`.
#include <nlohmann/json.hpp>

#include "drillwave/io/json_reader.hpp"
#include "drillwave/model/gear.hpp"
#include "drillwave/model/induction_motor.hpp"
#include "drillwave/model/pi_controller.hpp"

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

}  // namespace drillwave::cases
