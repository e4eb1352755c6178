#pragma once
// The diagnosis loop's outputs: diagnosis.json, fitted-case.json (runs as it is), case.json (the baseline as run),
// plot.svg and report.html — one self-contained page (inline SVG, no scripts, no outside resources) with the
// recording against the baseline and the fitted model, the residual of each feature before and after, the evidence
// and every candidate's scores.
#include <ostream>
#include <string>

#include "drillwave/diagnosis/loop.hpp"
#include "drillwave/diagnosis/recording.hpp"

namespace drillwave::diagnosis {

void WriteLoopHtml(const DiagnosisLoop& loop, const Recording& recording, std::ostream& out);

// Writes the files above into out_dir, all or nothing (io::OutputDirectory), and prediction.csv where a prediction
// past the recording is given (PredictFitted).
void WriteDiagnosisLoop(const DiagnosisLoop& loop, const Recording& recording, const std::string& out_dir,
                        const Recording* prediction = nullptr);

}  // namespace drillwave::diagnosis
