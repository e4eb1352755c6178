#pragma once
// The virtual sensor's report.html: what was estimated and how, the figure, the errors against the downhole channels
// the recording holds, the stick-slip events and the severity windows, read from estimate.json's content so that the
// page and the file cannot disagree.
#include <ostream>
#include <string>

#include <nlohmann/json.hpp>

#include "drillwave/io/svg_plot.hpp"

namespace drillwave::estimation {

// `summary`: EstimateSummary's content; `figure`: plot.svg's, drawn inline; `source`: the recording's name.
void WriteEstimateHtml(const std::string& source, const nlohmann::json& summary, const io::Figure& figure,
                       std::ostream& out);

}  // namespace drillwave::estimation
