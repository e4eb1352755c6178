#pragma once
// Squirrel-cage induction motor on a V/f supply (chapter eqs. 2.16-2.19). Pure functions of its parameters and
// states: the simulators own the states.
//
// The machine is the chapter's two-axis model written in the frame that turns with the supply voltage (electrical
// angular frequency w_e = 2 pi f) instead of the rotor flux: in that frame a steady run has constant fluxes, and the
// voltage is simply (V, 0). States: stator and rotor flux linkages psi_s, psi_r (complex: d + j q), with
//   psi_s' = v_s - R_s i_s - j w_e psi_s,       psi_r' = -R_r i_r - j (w_e - p w_m) psi_r,
//   [psi_s; psi_r] = [L_s L_m; L_m L_r] [i_s; i_r],   L_s = L_ls + L_m,  L_r = L_lr + L_m,
//   torque T = mu (psi_rd i_sq - psi_rq i_sd),  mu = 3 p L_m / (2 L_r)   (eq. 2.19: mu psi_rd I_sq in the rotor-flux
//   frame, where psi_rq = 0),
// amplitude-invariant axes: a phase voltage of rms V_ph is a space vector of length sqrt(2) V_ph. Supply: constant
// V/f, V_LL = volts_per_hertz f, limited to voltage_limit (field weakening above the base frequency). In steady state
// the torque is that of the per-phase equivalent circuit (Krause et al., Analysis of Electric Machinery, ch. 6), and
// with R_s = 0 it is Kloss' formula T = 2 T_k / (s / s_k + s_k / s).
#include <array>
#include <string>

namespace drillwave::model {

struct InductionMotor {
  int pole_pairs = 2;                     // p
  double stator_resistance = 0;           // R_s [ohm], per phase
  double rotor_resistance = 0;            // R_r [ohm], referred to the stator
  double stator_leakage_inductance = 0;   // L_ls [H]
  double rotor_leakage_inductance = 0;    // L_lr [H]
  double magnetizing_inductance = 0;      // L_m [H]
  double volts_per_hertz = 0;             // line-to-line rms voltage per hertz of supply [V/Hz]
  double voltage_limit = 0;               // line-to-line rms [V]; 0: none

  using Fluxes = std::array<double, 4>;   // psi_sd, psi_sq, psi_rd, psi_rq [Wb]

  // "" when the parameters make a machine, else what is wrong.
  std::string Problem() const;
  double StatorInductance() const { return stator_leakage_inductance + magnetizing_inductance; }
  double RotorInductance() const { return rotor_leakage_inductance + magnetizing_inductance; }
  // Line-to-line rms voltage at supply frequency f [Hz] (V/f, clamped to the limit; the sign follows f).
  double LineVoltage(double supply_hz) const;
  // Rates of the fluxes at supply frequency f and shaft speed w_m [rad/s].
  Fluxes FluxRates(const Fluxes& psi, double supply_hz, double shaft_speed) const;
  double Torque(const Fluxes& psi) const;            // electromagnetic torque on the shaft [N·m]
  double StatorCurrentRms(const Fluxes& psi) const;  // phase current, rms [A]
  // The fluxes that hold still at supply frequency f and constant shaft speed w_m.
  Fluxes SteadyFluxes(double supply_hz, double shaft_speed) const;
  // Small-slip torque per electrical slip frequency, dT / d(w_e - p w_m) = p (V/f)^2 / (4 pi^2 R_r) [N·m·s/rad] (the
  // R_s = 0 limit on the V/f line): what a slip-compensating drive divides a torque demand by.
  double SlipTorqueGain() const;
  // A V/f drive with slip-frequency control: the supply for a torque demand T at the measured shaft speed w_m,
  // f = (p w_m + s) / 2 pi with the slip frequency s = T / G held within the (R_s = 0) pull-out slip
  // R_r / (L_ls + L_lr), and the demand that asks for a given supply (its inverse inside that range).
  double SupplyForTorque(double torque_demand, double shaft_speed) const;
  double TorqueDemandFor(double supply_hz, double shaft_speed) const;
  double PullOutSlipFrequency() const { return rotor_resistance / (stator_leakage_inductance + rotor_leakage_inductance); }
  // The supply frequency at which the steady torque at shaft speed w_m is `torque` (below pull-out; the slip
  // frequency is bracketed by the R_s = 0 pull-out slip R_r / (L_ls + L_lr)). Throws std::domain_error if the
  // machine cannot give that torque there.
  double SteadySupplyFrequency(double torque, double shaft_speed) const;
};

}  // namespace drillwave::model
