#pragma once
// Periodic orbits of a case in one parameter (its JSON pointer): the steady states on a grid with their Hopf points,
// and from every Hopf point the branch of periodic orbits by pseudo-arclength continuation, with Floquet multipliers
// (saltation matrices at stick and slip) and folds (analysis/periodic_orbits.hpp). For `drillwave orbits`.
//
//   OrbitsSpec spec = ParseContinueOption("/model/upper_disc/input_voltage_V=0.3:6", doc);
//   WriteOrbitsOutputs(doc, spec, ContinueOrbits(doc, spec, nullptr), "out");
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "drillwave/analysis/periodic_orbits.hpp"

namespace drillwave::cases {

struct OrbitsSpec {
  std::string pointer;       // the parameter, e.g. /model/upper_disc/input_voltage_V
  std::vector<double> grid;  // steady states are computed here; the branches stay within [front, back]
};

// "POINTER=first:last" (201 grid values) or "POINTER=first:last:count". Throws ParameterError("continue", ...) naming
// the text for anything else, a pointer the case has no field at, a value the field refuses (both ends are parsed)
// and a kind without an orbit field.
OrbitsSpec ParseContinueOption(const std::string& text, const nlohmann::json& document);

// The model at parameter value p as a field (the document with p set, parsed).
analysis::FieldFamily CaseFieldFamily(const nlohmann::json& document, const std::string& pointer);

struct OrbitsResult {
  analysis::EquilibriumBranches equilibria;
  std::vector<analysis::HopfPoint> starts;          // the Hopf point each branch started from
  std::vector<analysis::PeriodicBranch> branches;  // none from a Hopf point an earlier branch ended at
  double wall_time_s = 0;
};

// progress(branch, points, p, period) after every continuation point.
using OrbitsProgress = std::function<void(int branch, int points, double p, double period)>;
OrbitsResult ContinueOrbits(const nlohmann::json& document, const OrbitsSpec& spec, const OrbitsProgress& progress);

// Ranges of grid values where a stable steady state coexists with a stable periodic orbit of a branch (bistability:
// the start decides), each from its first to its last such grid value.
std::vector<std::pair<double, double>> CoexistenceRanges(const OrbitsResult& result);

// orbits.csv (one row per equilibrium and per orbit: type, branch, parameter, period, amplitude measure = range of
// the last inertia's speed, its min and max, max |nontrivial Floquet multiplier|, stable, stick-slip flag), orbits.svg
// (bifurcation diagram), report.md (Hopf points, folds, how each branch ended), case.json; all or nothing.
void WriteOrbitsOutputs(const nlohmann::json& document, const OrbitsSpec& spec, const OrbitsResult& result,
                        const std::string& out_dir);

}  // namespace drillwave::cases
