#include "drillwave/diagnosis/inspection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "channel_figure.hpp"
#include "drillwave/core/error.hpp"
#include "drillwave/core/format.hpp"
#include "drillwave/core/progress.hpp"
#include "drillwave/core/validity.hpp"
#include "drillwave/io/axis_label.hpp"
#include "drillwave/io/json_number.hpp"
#include "drillwave/io/output_dir.hpp"
#include "drillwave/io/svg_plot.hpp"

namespace drillwave::diagnosis {
namespace {

constexpr std::size_t kAllPairsChannels = 24;  // above: correlations with the speeds only
constexpr std::size_t kPlottedChannels = 16;

bool Overlaps(const Interval& a, const Interval& b) { return a.begin_s <= b.end_s && b.begin_s <= a.end_s; }

nlohmann::json IntervalsToJson(const std::vector<Interval>& v) {
  nlohmann::json out = nlohmann::json::array();
  for (const Interval& i : v) out.push_back({i.begin_s, i.end_s});
  return out;
}

// Each channel's artefacts (Hampel outliers, bursts), its cleaned and its masked samples.
void FindArtefacts(const Recording& rec, const InspectOptions& o, Progress& progress, Inspection& ins) {
  const int half_window = std::max(1, static_cast<int>(std::lround(o.hampel_half_window_s / rec.sample_interval_s)));
  for (std::size_t j = 0; j < rec.names.size(); ++j) {
    progress.Count("artefacts of each channel", static_cast<double>(j), static_cast<double>(rec.names.size()),
                   "channels");
    const auto& x = rec.channels[j];
    std::vector<double> magnitude(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) magnitude[i] = std::abs(x[i]);
    const double floor = o.hampel_floor_fraction * Median(magnitude);
    HampelResult h = o.mask_artefacts
                         ? HampelFilter(x, half_window, o.hampel_threshold, floor, o.hampel_grow_threshold)
                         : HampelResult{x, std::vector<char>(x.size(), 0)};
    ChannelArtefacts a;
    a.channel = rec.names[j];
    a.samples_flagged = static_cast<int>(std::count(h.flagged.begin(), h.flagged.end(), 1));
    a.left_whole = TooManyForArtefacts(static_cast<std::size_t>(a.samples_flagged), x.size());
    if (a.left_whole) h = HampelResult{x, std::vector<char>(x.size(), 0)};
    a.bursts = Runs(rec.time_s, h.flagged, 3, 0.0);
    a.raw_min = *std::min_element(x.begin(), x.end()), a.raw_max = *std::max_element(x.begin(), x.end());
    a.clean_min = *std::min_element(h.cleaned.begin(), h.cleaned.end());
    a.clean_max = *std::max_element(h.cleaned.begin(), h.cleaned.end());
    ins.artefacts.push_back(a);
    ins.cleaned.push_back(std::move(h.cleaned));
    ins.masked.push_back(std::move(h.flagged));
  }
}

// The bit speed for regimes and periods: cleaned, then averaged over smoothing_s so that sensor noise about zero does
// not cut a stuck episode into pieces.
std::vector<double> SmoothedBitSpeed(const Recording& rec, const InspectOptions& o, const std::vector<double>& cleaned) {
  std::vector<double> bit = cleaned;
  const int half = static_cast<int>(std::lround(0.5 * o.smoothing_s / rec.sample_interval_s));
  if (half >= 1) {
    std::vector<double> prefix(cleaned.size() + 1, 0.0);
    for (std::size_t i = 0; i < cleaned.size(); ++i) prefix[i + 1] = prefix[i] + cleaned[i];
    const int n = static_cast<int>(cleaned.size());
    for (int i = 0; i < n; ++i) {
      const int lo = std::max(0, i - half), hi = std::min(n - 1, i + half);
      bit[i] = (prefix[hi + 1] - prefix[lo]) / (hi - lo + 1);
    }
  }
  return bit;
}

// The bit's stuck episodes, stick fraction, median period between onsets and long slips without sticking; the
// artefact bursts that fall in a stuck episode.
void FindStuckEpisodes(const Recording& rec, const InspectOptions& o, const std::vector<double>& bit, Inspection& ins) {
  std::vector<double> magnitude(bit.size());
  for (std::size_t i = 0; i < bit.size(); ++i) magnitude[i] = std::abs(bit[i]);
  ins.stuck_threshold = std::max(o.stuck_floor, o.stuck_fraction * Median(magnitude));
  std::vector<char> at_rest(bit.size());
  for (std::size_t i = 0; i < bit.size(); ++i) at_rest[i] = magnitude[i] < ins.stuck_threshold;
  ins.stuck = Runs(rec.time_s, at_rest, 0, o.stuck_min_s);
  double stuck_time = 0;
  for (const Interval& s : ins.stuck) stuck_time += s.duration();
  ins.stick_fraction = stuck_time / ins.duration_s;
  std::vector<double> onset_gaps;
  for (std::size_t k = 1; k < ins.stuck.size(); ++k) onset_gaps.push_back(ins.stuck[k].begin_s - ins.stuck[k - 1].begin_s);
  ins.stick_slip_period_s = onset_gaps.size() >= 1 ? Median(onset_gaps) : std::nan("");
  if (std::isfinite(ins.stick_slip_period_s)) {
    const double long_gap = o.slip_stretch_periods * ins.stick_slip_period_s;
    double from = rec.time_s.front();
    for (const Interval& s : ins.stuck) {
      if (s.begin_s - from > long_gap) ins.slip_without_stick.push_back({from, s.begin_s});
      from = s.end_s;
    }
    if (rec.time_s.back() - from > long_gap) ins.slip_without_stick.push_back({from, rec.time_s.back()});
  }
  for (ChannelArtefacts& a : ins.artefacts)
    for (const Interval& b : a.bursts)
      if (std::any_of(ins.stuck.begin(), ins.stuck.end(), [&](const Interval& s) { return Overlaps(b, s); }))
        ++a.bursts_while_stuck;

}

// Mean, extremes and spread of the two speeds.
void MeasureSpeeds(const std::vector<double>& bit, const std::vector<double>& top, Inspection& ins) {
  double sum = 0, max_bit = -std::numeric_limits<double>::infinity();
  for (double v : bit) sum += v, max_bit = std::max(max_bit, v);
  ins.bit_speed_mean = sum / bit.size(), ins.bit_speed_max = max_bit;
  sum = 0;
  for (double v : top) sum += v;
  ins.top_speed_mean = sum / top.size();
  double var = 0;
  for (double v : top) var += (v - ins.top_speed_mean) * (v - ins.top_speed_mean);
  ins.top_speed_std = std::sqrt(var / top.size());
  ins.top_speed_min = *std::min_element(top.begin(), top.end());
  ins.top_speed_max = *std::max_element(top.begin(), top.end());

}

// Top speed: fluctuation about a slow trend (set-point changes are not softness) against the sensor noise.
void MeasureTopFluctuation(const Recording& rec, const InspectOptions& o, const std::vector<double>& top,
                           Inspection& ins) {
  const std::size_t n = top.size();
  const int half = std::max(1, static_cast<int>(std::lround(0.5 * o.trend_window_s / rec.sample_interval_s)));
  const std::size_t stride = std::max<std::size_t>(1, static_cast<std::size_t>(half / 50));
  std::vector<double> knots_t, knots_v, window;
  for (std::size_t i = 0; i < n; i += stride) {
    const std::size_t lo = i >= static_cast<std::size_t>(half) ? i - half : 0, hi = std::min(n - 1, i + half);
    window.assign(top.begin() + static_cast<std::ptrdiff_t>(lo), top.begin() + static_cast<std::ptrdiff_t>(hi) + 1);
    knots_t.push_back(static_cast<double>(i));
    knots_v.push_back(Median(window));
  }
  double fluct = 0;
  std::size_t k = 0;
  for (std::size_t i = 0; i < n; ++i) {
    while (k + 1 < knots_t.size() && knots_t[k + 1] < i) ++k;
    const double trend = k + 1 < knots_t.size()
                             ? knots_v[k] + (knots_v[k + 1] - knots_v[k]) * (i - knots_t[k]) / (knots_t[k + 1] - knots_t[k])
                             : knots_v.back();
    fluct += (top[i] - trend) * (top[i] - trend);
  }
  ins.top_speed_fluctuation = std::sqrt(fluct / n);
  std::vector<double> diffs;
  for (std::size_t i = 1; i < n; ++i) diffs.push_back(std::abs(top[i] - top[i - 1]));
  ins.top_speed_noise = 1.4826 * Median(diffs) / std::sqrt(2.0);
  ins.top_speed_fluctuation_ratio = ins.top_speed_noise > 0 ? ins.top_speed_fluctuation / ins.top_speed_noise
                                                            : std::numeric_limits<double>::infinity();
  ins.top_drive_soft = ins.top_speed_fluctuation_ratio > o.soft_drive_ratio;
}

// Bit oscillation period: upward crossings of the mean with hysteresis (half a standard deviation either side), so
// that sensor noise about a steady speed does not count as oscillation.
void MeasureBitOscillation(const Recording& rec, const std::vector<double>& bit, Inspection& ins) {
  double var_bit = 0;
  for (double v : bit) var_bit += (v - ins.bit_speed_mean) * (v - ins.bit_speed_mean);
  const double band = 0.5 * std::sqrt(var_bit / bit.size());
  std::vector<double> crossings, gaps;
  bool armed = false;
  for (std::size_t i = 0; i < bit.size(); ++i) {
    if (bit[i] < ins.bit_speed_mean - band) armed = true;
    if (armed && bit[i] > ins.bit_speed_mean + band) crossings.push_back(rec.time_s[i]), armed = false;
  }
  for (std::size_t i = 1; i < crossings.size(); ++i) gaps.push_back(crossings[i] - crossings[i - 1]);
  ins.bit_oscillation_period_s = gaps.empty() ? std::nan("") : Median(gaps);
}

// Which channels move together: every pair of a few channels; with many, each channel with the two speeds only, so
// that the cost (and the size of the outputs) grows linearly with the number of channels.
void Correlate(const Recording& rec, std::size_t bit_index, std::size_t top_index, Inspection& ins) {
  const bool all_pairs = rec.names.size() <= kAllPairsChannels;
  for (std::size_t a = 0; a < rec.names.size(); ++a)
    for (std::size_t b = a + 1; b < rec.names.size(); ++b)
      if (all_pairs || a == bit_index || a == top_index || b == bit_index || b == top_index)
        ins.correlations.push_back({rec.names[a], rec.names[b], Correlation(ins.cleaned[a], ins.cleaned[b])});
  std::sort(ins.correlations.begin(), ins.correlations.end(), [](const ChannelPair& x, const ChannelPair& y) {
    return std::abs(x.correlation) > std::abs(y.correlation);
  });

}

// The findings, restating the numbers.
void WriteFindings(const Recording& rec, const InspectOptions& o, Inspection& ins) {
  auto& f = ins.findings;
  for (const ChannelArtefacts& a : ins.artefacts)
    if (a.left_whole)
      f.push_back(a.channel + ": " + std::to_string(a.samples_flagged) + " of " + std::to_string(rec.time_s.size()) +
                  " samples (" + Fixed(100.0 * a.samples_flagged / rec.time_s.size(), 1) + " %) look like artefacts: " +
                  "more than " + Fixed(100 * kMaxArtefactShare, 0) + " %, so they are taken for motion (a bouncing " +
                  "bit's impacts) and the channel is left whole.");
    else if (a.samples_flagged > 0)
      f.push_back(a.channel + ": " + std::to_string(a.samples_flagged) + " samples in " +
                  std::to_string(a.bursts.size()) + " bursts flagged as artefacts and masked (" +
                  std::to_string(a.bursts_while_stuck) + " bursts while the bit is at rest); range " +
                  Fixed(a.raw_min, 1) + " .. " + Fixed(a.raw_max, 1) + " raw, " + Fixed(a.clean_min, 1) + " .. " +
                  Fixed(a.clean_max, 1) + " cleaned.");
  f.push_back("bit at rest (|" + o.bit_speed + "| < " + Fixed(ins.stuck_threshold, 2) + ") in " +
              std::to_string(ins.stuck.size()) + " episodes, " + Fixed(100 * ins.stick_fraction, 1) +
              " % of the time; median interval between stick onsets " + Fixed(ins.stick_slip_period_s, 3) + " s.");
  double longest = 0;
  const Interval* longest_episode = nullptr;
  for (const Interval& s : ins.stuck)
    if (s.duration() > longest) longest = s.duration(), longest_episode = &s;
  if (longest_episode)
    f.push_back("longest stuck episode " + Fixed(longest, 3) + " s, from " + Fixed(longest_episode->begin_s, 2) +
                " s to " + Fixed(longest_episode->end_s, 2) + " s.");
  for (const Interval& s : ins.slip_without_stick)
    f.push_back("no stuck episode from " + Fixed(s.begin_s, 2) + " s to " + Fixed(s.end_s, 2) + " s (" +
                Fixed(s.duration() / ins.stick_slip_period_s, 1) + " median periods): the bit keeps turning there.");
  f.push_back(o.top_speed + " (cleaned): mean " + Fixed(ins.top_speed_mean, 2) + ", range " + Fixed(ins.top_speed_min, 1) +
              " .. " + Fixed(ins.top_speed_max, 1) + "; fluctuation about its " + Fixed(o.trend_window_s, 0) +
              "-s trend " + Fixed(ins.top_speed_fluctuation, 2) + " against sensor noise " +
              Fixed(ins.top_speed_noise, 2) + " (ratio " + Fixed(ins.top_speed_fluctuation_ratio, 1) + ")" +
              (ins.top_drive_soft ? ": the top speed is not held; the drive is soft, so model it (inertia and speed "
                                    "controller) rather than impose its speed."
                                  : ": the top speed is held (a stiff drive; imposing it is fine)."));
  f.push_back(o.bit_speed + " oscillates with a median period of " + Fixed(ins.bit_oscillation_period_s, 3) + " s.");
  for (const ChannelPair& p : ins.correlations)
    if (std::abs(p.correlation) >= 0.5)
      f.push_back(p.a + " and " + p.b + " move together: correlation " + Fixed(p.correlation, 2) + ".");
}

}  // namespace

bool InspectOptions::IsValid(std::string* error) const {
  auto named = [&](const char* parameter, const std::string& channel) {
    return !channel.empty() || Invalid(error, parameter, "expected a channel name, got an empty one");
  };
  return named("bit_speed", bit_speed) && named("top_speed", top_speed) &&
         PositiveField(error, "hampel_half_window_s", hampel_half_window_s) &&
         PositiveField(error, "hampel_threshold", hampel_threshold) &&
         PositiveField(error, "hampel_grow_threshold", hampel_grow_threshold) &&
         NonNegativeField(error, "hampel_floor_fraction", hampel_floor_fraction) &&
         FractionField(error, "stuck_fraction", stuck_fraction) &&
         NonNegativeField(error, "stuck_floor", stuck_floor) && NonNegativeField(error, "stuck_min_s", stuck_min_s) &&
         NonNegativeField(error, "smoothing_s", smoothing_s) &&
         PositiveField(error, "slip_stretch_periods", slip_stretch_periods) &&
         PositiveField(error, "trend_window_s", trend_window_s) &&
         PositiveField(error, "soft_drive_ratio", soft_drive_ratio);
}

Inspection InspectRecording(const Recording& rec, const InspectOptions& o) {
  ThrowIfInvalid(o);
  rec.Channel(o.bit_speed);  // both are needed; fail early, naming the one that is missing
  rec.Channel(o.top_speed);
  Inspection ins;
  ins.source = rec.source;
  ins.bit_speed = o.bit_speed;
  ins.top_speed = o.top_speed;
  ins.duration_s = rec.time_s.back() - rec.time_s.front();
  ins.sample_interval_s = rec.sample_interval_s;
  Progress progress("inspect " + ReadableText(rec.source, 200));
  FindArtefacts(rec, o, progress, ins);
  auto index = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(rec.names.begin(), rec.names.end(), name) - rec.names.begin());
  };
  const std::size_t bit_index = index(o.bit_speed), top_index = index(o.top_speed);
  const std::vector<double> bit = SmoothedBitSpeed(rec, o, ins.cleaned[bit_index]);
  const std::vector<double>& top = ins.cleaned[top_index];
  progress.Step("the bit's stuck episodes");
  FindStuckEpisodes(rec, o, bit, ins);
  MeasureSpeeds(bit, top, ins);
  progress.Step("the top speed's fluctuation");
  MeasureTopFluctuation(rec, o, top, ins);
  MeasureBitOscillation(rec, bit, ins);
  progress.Step("which channels move together");
  Correlate(rec, bit_index, top_index, ins);
  WriteFindings(rec, o, ins);
  return ins;
}

nlohmann::json InspectionToJson(const Inspection& ins) {
  nlohmann::json artefacts = nlohmann::json::array();
  for (const ChannelArtefacts& a : ins.artefacts)
    artefacts.push_back({{"channel", a.channel},
                         {"samples_flagged", a.samples_flagged},
                         {"left_whole", a.left_whole},
                         {"bursts", IntervalsToJson(a.bursts)},
                         {"bursts_while_stuck", a.bursts_while_stuck},
                         {"raw_range", {a.raw_min, a.raw_max}},
                         {"cleaned_range", {a.clean_min, a.clean_max}}});
  nlohmann::json correlations = nlohmann::json::array();
  for (const ChannelPair& p : ins.correlations) correlations.push_back({p.a, p.b, p.correlation});
  return {{"source", ins.source},
          {"duration_s", io::FiniteOrNull(ins.duration_s)},
          {"sample_interval_s", ins.sample_interval_s},
          {"artefacts", artefacts},
          {"stuck_threshold", ins.stuck_threshold},
          {"stuck_episodes_s", IntervalsToJson(ins.stuck)},
          {"slip_without_stick_s", IntervalsToJson(ins.slip_without_stick)},
          {"stick_fraction", ins.stick_fraction},
          {"stick_slip_period_s", io::FiniteOrNull(ins.stick_slip_period_s)},
          {"bit_speed_mean", io::FiniteOrNull(ins.bit_speed_mean)},
          {"bit_speed_max", io::FiniteOrNull(ins.bit_speed_max)},
          {"top_speed",
           {{"mean", ins.top_speed_mean},
            {"std", ins.top_speed_std},
            {"min", ins.top_speed_min},
            {"max", ins.top_speed_max},
            {"fluctuation", ins.top_speed_fluctuation},
            {"noise", ins.top_speed_noise},
            {"fluctuation_ratio", io::FiniteOrNull(ins.top_speed_fluctuation_ratio)},
            {"drive_soft", ins.top_drive_soft}}},
          {"bit_oscillation_period_s", io::FiniteOrNull(ins.bit_oscillation_period_s)},
          {"correlations", correlations},
          {"findings", ins.findings}};
}

namespace {

// The channels plotted: the speeds first, then the others in the file's order, at most kPlottedChannels of them (the
// report says which are left out).
std::vector<std::size_t> PlottedChannels(const Recording& rec, const Inspection& ins) {
  std::vector<std::size_t> plotted;
  for (const std::string& name : {ins.bit_speed, ins.top_speed})
    for (std::size_t j = 0; j < rec.names.size(); ++j)
      if (rec.names[j] == name && std::find(plotted.begin(), plotted.end(), j) == plotted.end()) plotted.push_back(j);
  for (std::size_t j = 0; j < rec.names.size() && plotted.size() < kPlottedChannels; ++j)
    if (std::find(plotted.begin(), plotted.end(), j) == plotted.end()) plotted.push_back(j);
  return plotted;
}

// 1 while the bit is at rest (in a stuck episode), 0 otherwise, at each sample.
std::vector<double> AtRest(const Recording& rec, const Inspection& ins) {
  std::vector<double> stuck(rec.time_s.size(), 0.0);
  std::size_t k = 0;
  for (std::size_t i = 0; i < rec.time_s.size(); ++i) {
    while (k < ins.stuck.size() && ins.stuck[k].end_s < rec.time_s[i]) ++k;
    stuck[i] = k < ins.stuck.size() && ins.stuck[k].begin_s <= rec.time_s[i] ? 1.0 : 0.0;
  }
  return stuck;
}

// Channel j as recorded over [from_s, to_s], its masked samples apart.
std::vector<io::Series> Recorded(const Recording& rec, const Inspection& ins, std::size_t j, double from_s,
                                 double to_s) {
  return figure_internal::RecordedSeries(rec.names[j], rec.time_s, rec.channels[j],
                                         j < ins.masked.size() ? ins.masked[j] : std::vector<char>{}, from_s, to_s);
}

}  // namespace

io::Figure InspectionFigure(const Recording& rec, const Inspection& ins) {
  io::Figure figure;
  figure.title = "inspection of " + rec.source;
  figure.x_label = "time [s]";
  const double begin = rec.time_s.front(), end = rec.time_s.back();
  for (const std::size_t j : PlottedChannels(rec, ins))
    figure.panels.push_back({io::AxisLabelOfChannels({rec.names[j]}), Recorded(rec, ins, j, begin, end)});
  figure.panels.push_back({"bit at rest", {{"bit at rest (1)", rec.time_s, AtRest(rec, ins)}}});
  // Stick-slip cycles are too short to read over a whole recording: the bit speed's last few again, on a time axis
  // of their own (the stick-slip period, or where the bit never sticks, its oscillation's).
  const auto bit = std::find(rec.names.begin(), rec.names.end(), ins.bit_speed);
  if (bit == rec.names.end()) return figure;
  const double period =
      std::isfinite(ins.stick_slip_period_s) ? ins.stick_slip_period_s : ins.bit_oscillation_period_s;
  const figure_internal::Zoom zoom = figure_internal::LastCycles(period, begin, end, figure.x_label, "recording");
  const std::size_t j = static_cast<std::size_t>(bit - rec.names.begin());
  figure.panels.push_back(figure_internal::ZoomPanel(io::AxisLabelOfChannels({ins.bit_speed}),
                                                     Recorded(rec, ins, j, zoom.from_s, zoom.to_s), zoom));
  return figure;
}

void WriteInspection(const Recording& rec, const Inspection& ins, const std::string& out_dir) {
  io::OutputDirectory out(out_dir);
  out.Open("findings.json") << InspectionToJson(ins).dump(2) << "\n";

  io::WriteSvg(InspectionFigure(rec, ins), out.Open("plot.svg"));

  std::ostream& report = out.Open("report.md");
  report << "# Inspection of " << rec.source << "\n\n"
         << rec.names.size() << " channels, " << rec.time_s.size() << " samples every " << ins.sample_interval_s
         << " s (" << ins.duration_s << " s).\n\n## Findings\n\n";
  for (const std::string& f : ins.findings) report << "- " << f << "\n";
  report << "\n## Stuck episodes of the bit\n\n| from [s] | to [s] | duration [s] |\n|---|---|---|\n";
  for (const Interval& s : ins.stuck)
    report << "| " << Fixed(s.begin_s, 3) << " | " << Fixed(s.end_s, 3) << " | " << Fixed(s.duration(), 3) << " |\n";
  report << "\n## Correlations of the cleaned channels\n\n| channels | correlation |\n|---|---|\n";
  for (const ChannelPair& p : ins.correlations) report << "| " << p.a << ", " << p.b << " | " << Fixed(p.correlation, 3) << " |\n";
  if (rec.names.size() > kAllPairsChannels)
    report << "\nWith " << rec.names.size() << " channels (more than " << kAllPairsChannels
           << "), each channel is correlated with the two speeds only.\n";
  const std::size_t plotted = PlottedChannels(rec, ins).size();
  if (plotted < rec.names.size())
    report << "\n`plot.svg` shows " << plotted << " of the " << rec.names.size()
           << " channels (the speeds first, then in the file's order).\n";
  report << "\nFiles: `findings.json` (every number above), `plot.svg` (each channel as recorded, its masked samples "
            "as grey dots; the stuck flag; the bit speed's last few stick-slip cycles zoomed).\n";
  out.Commit();
}

}  // namespace drillwave::diagnosis
