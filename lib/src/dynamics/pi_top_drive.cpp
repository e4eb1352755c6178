#include "drillwave/dynamics/pi_top_drive.hpp"

#include <algorithm>
#include <limits>

namespace drillwave::dynamics {

PiTopDrive::PiTopDrive(const model::PiController& pi, const model::TopDriveLaw& law, const model::Schedule& setpoint,
                       double initial_speed, double inertia)
    : pi_(pi), law_(law), setpoint_(setpoint), inertia_(inertia) {
  if (delay() > 0)  // the drive's speed as its delayed controller reads it; steady before the start
    speed_history_.emplace(1, [initial_speed](double, double* value, double* rate) {
      *value = initial_speed, *rate = 0;
    });
}

bool PiTopDrive::Engaged(double t, Side side) const {
  const model::Handover& h = law_.handover;
  return !h.active() || t > h.time_s || (t == h.time_s && side == Side::kRight);
}

double PiTopDrive::InitialIntegral(double held, double string_torque) const {
  if (CancelsWaves(0.0, Side::kRight)) return pi_.IntegralHolding(string_torque);
  return PiAt(0.0, Side::kRight).IntegralHolding(held);
}

// u = T_load + J (w' + d') + kp (w + d - v) (model::WaveCancellation), everything as read; d' from the set-point's
// slope and the integral's rate, through the same linear DownWave. Filtered, the low-passed wave a and its rate
// (w - a) / tf stand for w and w'.
double PiTopDrive::WaveCancellingTorque(const Reading& in, double integral) const {
  const model::WaveCancellation& law = law_.wave_cancellation;
  const double down = law.DownWave(in.command, pi_.ki * integral);
  const double down_rate = law.DownWave(in.command_rate, pi_.ki * IntegralRate(in));
  const double wave = law.filtered() ? in.low_passed : in.wave.arriving;
  const double wave_rate = law.filtered() ? law.FilterRate(in.wave.arriving, in.low_passed) : in.wave.arriving_rate;
  return in.wave.load + inertia_ * (wave_rate + down_rate) + pi_.kp * (wave + down - in.speed);
}

double PiTopDrive::MaxStep(double process_max_step) const {
  return delay() > 0 ? std::min(process_max_step, delay()) : process_max_step;
}

double PiTopDrive::NextBreakpoint(double passed) const {
  double next = law_.handover.active() && law_.handover.time_s > passed ? law_.handover.time_s
                                                                         : std::numeric_limits<double>::infinity();
  if (delay() > 0) {  // passed - delay may round below the knot just passed a delay late: skip it
    double knot = setpoint_.NextKnotAfter(passed - delay());
    while (knot + delay() <= passed) knot = setpoint_.NextKnotAfter(knot);
    next = std::min(next, knot + delay());
  }
  return next;
}

void PiTopDrive::OnBreakpoint(double t, double& integral) {
  restarted_ = true;
  const model::Handover& h = law_.handover;
  if (!h.active() || handed_over_ || t < h.time_s) return;
  handed_over_ = true;
  integral *= h.before.ki / pi_.ki;  // the reader asks for ki > 0 with a handover
}

void PiTopDrive::Commit(const integration::Piece& p, int v, double read_back) {
  if (speed_history_) {
    speed_history_->Append(p.t0, &p.x0[v], &p.f0[v], p.t1, &p.x1[v], &p.f1[v], &p.x_mid[v], restarted_);
    speed_history_->DiscardBefore(p.t1 - read_back);
  }
  restarted_ = false;
}

}  // namespace drillwave::dynamics
