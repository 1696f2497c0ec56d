#include "tactile/segment/fit.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>

#include "tactile/error.h"
#include "tactile/segment/adaptive.h"
#include "tactile/segment/presets.h"
#include "tactile/text.h"

namespace tactile {

namespace {

// A part of the labels that is scored as one: a recording's touches (or a block of them) and
// the stretch they cover.
struct FitUnit {
  size_t recording = 0;
  std::vector<Label> touches;
  double from = 0.0, to = 0.0;
};

FitUnit fit_unit(size_t recording, std::vector<Label> touches) {
  FitUnit unit;
  unit.recording = recording;
  unit.from = touches.front().t0;
  unit.to = touches.front().t1;
  for (const Label& touch : touches) {
    unit.from = std::min(unit.from, touch.t0);
    unit.to = std::max(unit.to, touch.t1);
  }
  unit.touches = std::move(touches);
  return unit;
}

// The unit's touches against the segments that overlap its stretch, over its frames.
TouchScore fit_unit_score(const FitUnit& unit, const Stream& stream,
                          const std::vector<Label>& segments) {
  std::vector<Label> inside;
  for (const Label& segment : segments)
    if (segment.t1 > unit.from && segment.t0 < unit.to) inside.push_back(segment);
  const double start = stream.time_of(0);
  const double rate = stream.rate_hz;
  const auto first = static_cast<int64_t>(std::ceil((unit.from - start) * rate - 1e-9));
  const auto end = static_cast<int64_t>(std::ceil((unit.to - start) * rate - 1e-9));
  return score_touches(inside, unit.touches, start + static_cast<double>(first) / rate, rate,
                       std::max<int64_t>(0, end - first));
}

// Better: higher event F1, then higher frame F1.
bool fit_better(const TouchScore& a, const TouchScore& b) {
  if (a.events.f1() != b.events.f1()) return a.events.f1() > b.events.f1();
  return a.frames.f1() > b.frames.f1();
}

// The candidate that scores best over `units` (all but `left_out`).
size_t fit_choose(const std::vector<std::vector<TouchScore>>& scores, size_t left_out) {
  size_t best = 0;
  TouchScore best_score;
  for (size_t k = 0; k < scores.size(); ++k) {
    TouchScore total;
    for (size_t u = 0; u < scores[k].size(); ++u)
      if (u != left_out) total += scores[k][u];
    if (k == 0 || fit_better(total, best_score)) best = k, best_score = total;
  }
  return best;
}

}  // namespace

std::vector<std::string> segmenter_fit_candidates() {
  std::vector<std::string> candidates;
  for (const char* share : {"0.2", "0.1", "0.15", "0.3", "0.4"})
    for (const char* footprint : {"0.1", "0.05", "0.2"})
      for (const char* taxels : {"2", "1"})
        for (const char* join : {"-1", "0", "0.1", "0.2", "0.4", "0.8"})
          candidates.push_back(std::string("share=") + share + ",footprint=" + footprint +
                               ",taxels=" + taxels + ",join_seconds=" + join);
  return candidates;
}

SegmenterFit fit_segmenter(const std::vector<FitRecording>& recordings,
                           const std::function<void(double)>& progress) {
  SegmenterFit fit;
  for (const FitRecording& item : recordings) {
    if (item.recording == nullptr || item.layout == nullptr)
      throw Error("fit", "a recording or its layout is missing");
    if (item.touches.empty()) continue;
    if (item.recording->streams.empty()) throw Error(item.recording->id, "no stream to segment");
    const Stream& stream = item.recording->streams.front();
    const double start = stream.sample_count() > 0 ? stream.time_of(0) : 0.0;
    const double end = stream.sample_count() > 0
                           ? stream.time_of(stream.sample_count() - 1) + 1.0 / stream.rate_hz
                           : start;
    for (const Label& touch : item.touches)
      if (touch.t0 < start - 1e-9 || touch.t1 > end + 1e-9)
        throw Error(item.recording->id,
                    "label " + fixed_text(touch.t0, 3) + "-" + fixed_text(touch.t1, 3) +
                        " s lies outside the recording (" + fixed_text(start, 3) + "-" +
                        fixed_text(end, 3) + " s): fix or remove it, then fit again");
    fit.touches += static_cast<int64_t>(item.touches.size());
  }
  if (fit.touches < 3)
    throw Error("fit", "needs at least three labelled touches, has " + std::to_string(fit.touches) +
                           ": label three or more touches in the lane, then fit again");

  // The units: a recording each, or with one labelled recording, three blocks of its touches.
  std::vector<size_t> labelled;
  for (size_t r = 0; r < recordings.size(); ++r)
    if (!recordings[r].touches.empty()) labelled.push_back(r);
  std::vector<FitUnit> units;
  if (labelled.size() >= 2) {
    for (size_t r : labelled) units.push_back(fit_unit(r, recordings[r].touches));
    fit.folds = "by recording (" + std::to_string(units.size()) + " folds)";
  } else {
    std::vector<Label> touches = recordings[labelled.front()].touches;
    std::sort(touches.begin(), touches.end(),
              [](const Label& a, const Label& b) { return a.t0 < b.t0; });
    const size_t blocks = 3;
    for (size_t b = 0; b < blocks; ++b) {
      const size_t from = b * touches.size() / blocks, to = (b + 1) * touches.size() / blocks;
      units.push_back(
          fit_unit(labelled.front(), {touches.begin() + static_cast<std::ptrdiff_t>(from),
                                      touches.begin() + static_cast<std::ptrdiff_t>(to)}));
    }
    fit.folds = "by time blocks (" + std::to_string(blocks) + " folds)";
  }

  // Every candidate on every unit: one scan per recording, a fast decision per candidate.
  const std::vector<std::string> candidates = segmenter_fit_candidates();
  fit.candidates = static_cast<int64_t>(candidates.size());
  std::vector<std::vector<TouchScore>> scores(candidates.size(),
                                              std::vector<TouchScore>(units.size()));
  for (size_t l = 0; l < labelled.size(); ++l) {
    const FitRecording& item = recordings[labelled[l]];
    const AdaptiveSegmenter segmenter(*item.recording, *item.layout, Parameters{});
    for (size_t k = 0; k < candidates.size(); ++k) {
      const std::vector<Label> segments =
          segmenter.segments(Parameters::parse(candidates[k], "fit candidate"));
      for (size_t u = 0; u < units.size(); ++u)
        if (units[u].recording == labelled[l])
          scores[k][u] = fit_unit_score(units[u], item.recording->streams.front(), segments);
      if (progress)
        progress((static_cast<double>(l) +
                  static_cast<double>(k + 1) / static_cast<double>(candidates.size())) /
                 static_cast<double>(labelled.size()));
    }
  }
  for (size_t u = 0; u < units.size(); ++u) fit.held_out += scores[fit_choose(scores, u)][u];
  const size_t chosen = fit_choose(scores, units.size());
  fit.params = candidates[chosen];
  for (size_t u = 0; u < units.size(); ++u) fit.fitted += scores[chosen][u];
  return fit;
}

SegmenterPreset fit_preset(const SegmenterFit& fit, const std::string& name,
                           const std::string& lane) {
  SegmenterPreset preset;
  preset.name = name;
  preset.method = fit.method;
  preset.params = fit.params;
  preset.fitted_to = lane;
  preset.held_out_event_f1 = fit.held_out.events.f1();
  preset.touches = fit.touches;
  return preset;
}

std::string touch_score_text(const TouchScore& score) {
  std::ostringstream out;
  out << "frame F1 " << fixed_text(score.frames.f1(), 3) << " (precision "
      << fixed_text(score.frames.precision(), 3) << ", recall "
      << fixed_text(score.frames.recall(), 3) << "), event F1 " << fixed_text(score.events.f1(), 3)
      << " (" << score.events.hits << " of " << score.touches << " touches found, "
      << score.events.false_alarms << " false alarms; " << score.segments << " segments), "
      << score.split << " touches split, " << score.merged << " merged";
  return out.str();
}

std::string fit_report(const SegmenterFit& fit) {
  std::ostringstream out;
  out << "fitted " << fit.method << " to " << fit.touches << " labelled touches (" << fit.candidates
      << " parameter sets tried): " << fit.params << "\n"
      << "  held out, " << fit.folds << ": " << touch_score_text(fit.held_out) << "\n"
      << "  on the touches it was fitted to: " << touch_score_text(fit.fitted) << "\n";
  return out.str();
}

}  // namespace tactile
