#include "tactile/segment/frame_edge.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "tactile/dsp/tsa_preprocess.h"
#include "tactile/error.h"

namespace tactile {

std::vector<int> occupancy_changes(const std::vector<uint8_t>& active) {
  std::vector<int> changes;
  for (size_t n = 0; n + 1 < active.size(); ++n)
    // TSA eq. (4): Ccov^n = f(n+1) - f(n).
    changes.push_back(static_cast<int>(active[n + 1] != 0) - static_cast<int>(active[n] != 0));
  return changes;
}

std::vector<FrameEvent> frame_events(const std::vector<uint8_t>& active, int64_t gap,
                                     bool keep_open) {
  std::vector<FrameEvent> events;
  const auto frames = static_cast<int64_t>(active.size());
  int64_t n = 0;
  while (n < frames) {
    if (!active[n]) {
      ++n;
      continue;
    }
    // Rising edge at n (frames before the stream count as f = 0); extend while the next
    // active frame is within `gap` inactive frames.
    FrameEvent event{n, n, false};
    int64_t next = n + 1;
    while (true) {
      while (next < frames && active[next]) event.last = next++;
      int64_t resume = next;
      while (resume < frames && !active[resume] && resume - next < gap) ++resume;
      if (resume < frames && active[resume] && resume > next) {
        next = resume;
        continue;
      }
      break;
    }
    // Falling edge: the frame after the last active one must exist and be inactive.
    event.open = event.last + 1 >= frames;
    if (!event.open || keep_open) events.push_back(event);
    n = event.last + 1;
  }
  return events;
}

std::vector<Label> segment_frame_edge(const Recording& recording, const SkinLayout& layout,
                                      const Parameters& parameters) {
  std::vector<std::string> known = dsp::tsa_preprocess_keys();
  known.insert(known.end(), {"gap", "keep_open", "events_per"});
  parameters.expect_only(known);
  const int64_t gap = parameters.integer("gap", 0);
  if (gap < 0) throw Error(parameters.where(), "gap must not be negative");
  const bool keep_open = parameters.flag("keep_open", false);
  const std::string events_per = parameters.text("events_per", "location");
  if (events_per != "location" && events_per != "sheet")
    throw Error(parameters.where(), "events_per=" + events_per + ": expected location or sheet");

  const Recording contacts =
      dsp::tsa_preprocess(recording, layout, dsp::tsa_preprocess_options(parameters));
  const Stream& stream = dsp::tsa_stream(contacts);
  const std::vector<dsp::TsaSheet> sheets = dsp::tsa_sheets(layout, stream);
  const int64_t frames = stream.sample_count();

  // Active frames of each sheet: some pad triggered (a missing sample is not a contact).
  std::vector<std::vector<uint8_t>> sheet_active(sheets.size(), std::vector<uint8_t>(frames, 0));
  for (size_t s = 0; s < sheets.size(); ++s)
    for (int column : sheets[s].columns) {
      const float* values = stream.samples.col(column).data();
      for (int64_t n = 0; n < frames; ++n) sheet_active[s][n] |= values[n] > 0.0f;
    }

  // Sheets that form one surface: the location group, or each sheet alone.
  std::map<std::string, std::vector<size_t>> surfaces;
  std::vector<std::string> surface_order;
  for (size_t s = 0; s < sheets.size(); ++s) {
    const std::string& surface = (events_per == "location" && !sheets[s].location.empty())
                                     ? sheets[s].location
                                     : sheets[s].id;
    if (!surfaces.count(surface)) surface_order.push_back(surface);
    surfaces[surface].push_back(s);
  }

  std::vector<Label> labels;
  for (const std::string& surface : surface_order) {
    const std::vector<size_t>& members = surfaces[surface];
    std::vector<uint8_t> active(frames, 0);
    for (size_t s : members)
      for (int64_t n = 0; n < frames; ++n) active[n] |= sheet_active[s][n];
    for (const FrameEvent& event : frame_events(active, gap, keep_open)) {
      // Spec §2.1: the event belongs to the sheet with the most active frames (first on ties).
      size_t best = members.front();
      int64_t best_count = -1;
      for (size_t s : members) {
        const auto begin = sheet_active[s].begin();
        const int64_t count = std::count(begin + event.first, begin + event.last + 1, uint8_t{1});
        if (count > best_count) {
          best_count = count;
          best = s;
        }
      }
      Label label;
      label.recording = recording.id;
      label.t0 = stream.time_of(event.first);
      label.t1 = event.last + 1 < frames ? stream.time_of(event.last + 1)
                                         : stream.time_of(event.last) + 1.0 / stream.rate_hz;
      label.region = sheets[best].location.empty() ? sheets[best].id : sheets[best].location;
      label.annotator = "segmenter:frame-edge";
      label.source = LabelSource::kSegmenter;
      label.note = "sheet=" + sheets[best].id +
                   " frames=" + std::to_string(event.last - event.first + 1) +
                   (event.open ? " truncated" : "");
      labels.push_back(std::move(label));
    }
  }
  std::stable_sort(labels.begin(), labels.end(),
                   [](const Label& a, const Label& b) { return a.t0 < b.t0; });
  return labels;
}

}  // namespace tactile
