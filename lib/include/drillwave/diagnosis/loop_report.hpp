#pragma once
// The diagnosis loop's outputs: diagnosis.json, fitted-case.json (runs as it is), case.json (the baseline as run),
// plot.svg and report.html — one self-contained page (inline SVG, no scripts, no outside resources) with the
// recording against the baseline and the fitted model, the residual of each feature before and after, the evidence
// and every candidate's scores.
#include <ostream>
#include <string>

#include "drillwave/diagnosis/loop.hpp"
#include "drillwave/diagnosis/recording.hpp"
#include "drillwave/io/svg_plot.hpp"

namespace drillwave::diagnosis {

// The figure of plot.svg and the report: each mapped channel over the fit and held-out windows, the recording (its
// samples masked as artefacts as dots apart from its line) against the baseline and the fitted model; then the bit
// speed zoomed on the held-out window's last few stick-slip cycles.
io::Figure DiagnosisFigure(const DiagnosisLoop& loop, const Recording& recording);

void WriteLoopHtml(const DiagnosisLoop& loop, const Recording& recording, std::ostream& out);

// Writes the files above into out_dir, all or nothing (io::OutputDirectory), and prediction.csv where a prediction
// past the recording is given (PredictFitted).
void WriteDiagnosisLoop(const DiagnosisLoop& loop, const Recording& recording, const std::string& out_dir,
                        const Recording* prediction = nullptr);

}  // namespace drillwave::diagnosis
