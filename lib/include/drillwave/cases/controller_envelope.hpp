#pragma once
// Stick-slip-free envelopes of the top-drive laws (issue 35): each law of a nominal comparison, tuned there as a
// drive is commissioned and then held fixed, mapped over two parameters of the case (the top speed set-point and the
// weight on bit, say) by StabilityMap2D: the linear verdict at every grid point and the regime a run reaches under
// the comparison's protocol (the stiff PI's stick-slip, then the law from the handover to the end of the window).
//
//   ControllerComparison nominal = CompareControllers(document, {});
//   ControllerEnvelopes e = MapControllerEnvelopes(nominal, {ParseMapAxis("/model/top/speed_rad_s/knots/1/1=4:12:5",
//                                                  document), ParseMapAxis("/model/bit/friction/W_N=8e4:1.2e5:5",
//                                                  document)});
//   WriteControllerComparison(document, nominal, "out", {&e, {}});  // envelopes.csv, envelopes.svg, the table
#include <ostream>
#include <string>
#include <vector>

#include "drillwave/cases/controller_comparison.hpp"
#include "drillwave/cases/stability_map.hpp"

namespace drillwave::cases {

struct LawEnvelope {
  std::string law;
  StabilityMapResult map;
  // Grid points free of stick-slip by the linear verdict (LinearlySteady: stable or marginal), those of them only
  // marginal, and those free by simulation (the smooth regime).
  int linear_free = 0, marginal = 0, simulated_free = 0;
  // Boundary points: grid points whose linear verdict (free or not) differs from that of a neighbour along an axis;
  // at how many of them the run agrees with the linear verdict (smooth where free, not smooth where not).
  int boundary = 0, boundary_agreeing = 0;
  // Grid points whose simulated regime (free or not) differs from that of a neighbour: the envelope as the runs draw
  // it, where the linear verdict has no boundary (one mode unstable over the whole grid, e.g. the coupled strings'
  // axial regenerative mode, whatever the top-drive law).
  int simulated_boundary = 0;
};

struct ControllerEnvelopes {
  MapAxis x, y;
  std::vector<LawEnvelope> laws;  // in the nominal comparison's order
};

// Throws InputError as StabilityMap2D does (a grid point the law's case refuses names the pointers and values).
ControllerEnvelopes MapControllerEnvelopes(const ControllerComparison& nominal, const MapAxis& x, const MapAxis& y,
                                           int jobs = 1);

// envelopes.csv: a row per law and grid point (law, p1, p2, verdict, rightmost_re_per_s, regime, stick_fraction,
// severity, boundary).
void WriteEnvelopeCsv(const ControllerEnvelopes& envelopes, std::ostream& out);
// envelopes.svg: a stability map per law, one under the other (linear verdict as colour, simulated regime as marker).
void WriteEnvelopeSvg(const std::string& name, const ControllerEnvelopes& envelopes, std::ostream& out);
// The Markdown section of controllers.md: the axes and a row per law.
void WriteEnvelopeMarkdown(const ControllerEnvelopes& envelopes, std::ostream& out);

}  // namespace drillwave::cases
