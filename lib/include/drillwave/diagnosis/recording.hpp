#pragma once
// Diagnosis reads recordings (recordings/recording.hpp) with the signal tools of recordings/signals.hpp: their names, in
// diagnosis's namespace.
#include "drillwave/recordings/recording.hpp"
#include "drillwave/recordings/signals.hpp"

namespace drillwave::diagnosis {

using recordings::Correlation;
using recordings::HampelFilter;
using recordings::HampelResult;
using recordings::Interval;
using recordings::kMaxArtefactShare;
using recordings::LoadRecording;
using recordings::MaskArtefacts;
using recordings::MaskedRecording;
using recordings::Mean;
using recordings::Median;
using recordings::Recording;
using recordings::Runs;
using recordings::Std;
using recordings::TooManyForArtefacts;

}  // namespace drillwave::diagnosis
