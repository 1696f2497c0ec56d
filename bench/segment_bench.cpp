// Touches found against touches labelled, on every kind of data in one table (issue 40):
// the simulated skins clean and with realistic faults, the development recordings of a real
// grid that people labelled (--dev FOLDER), and three signals made here with known touches
// (clean pulses, a binary 0/1 strip, a saturating 8-bit grid). Columns: the ten-line baseline,
// the skin's own segmenter, `adaptive` with its defaults, and `adaptive` fitted
// (segment/fit.h) to the first five labelled touches of each recording, scored on the touches
// after them. Scores: segment/scoring.h's score_touches (the development set's README's
// definitions). bench/SEGMENT.md has the table.
//
//   build/bench/segment_bench [--subjects N] [--seed S] [--faults realistic|SPEC]
//                             [--params ADAPTIVE_PARAMS] [--dev FOLDER] [--no-sim] [skin ...]
//
// --dev FOLDER: every .h5 under FOLDER with the ground truth in FOLDER/labels.db (the
// development set imported as its README says). Without skins: every skin with a simulator
// (skins/skin.h) and the pressure grids grid:16x16 and grid:19x27 (sim/grid_sim.h).
//
// The baseline, made general from the development set's README's: each channel's median is
// its rest; a channel is on 40/255 of the skin's range above it (the largest rise of any
// channel above its rest; 40 counts on an 8-bit grid); a frame is a touch with min(3,
// ceil(channels / 8)) channels on; one frame of dilation.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/segment/fit.h"
#include "tactile/segment/scoring.h"
#include "tactile/segment/segmenter.h"
#include "tactile/sim/grid_sim.h"
#include "tactile/sim/sensor_faults.h"
#include "tactile/skins/skin.h"
#include "tactile/stats/statistics.h"

namespace {

using tactile::Label;
using tactile::Recording;
using tactile::TouchScore;

// A recording, its layout and its labelled touches.
struct Labelled {
  Recording recording;
  tactile::SkinLayout layout;
  std::vector<Label> touches;
};

std::vector<Label> baseline_touches(const Recording& recording) {
  const tactile::Stream& stream = recording.streams.front();
  const auto channels = static_cast<int>(stream.channel_count());
  const int64_t samples = stream.sample_count();
  std::vector<float> rest(static_cast<size_t>(channels), 0.0f);
  float range = 0.0f;
  for (int c = 0; c < channels; ++c) {
    std::vector<float> values(stream.samples.col(c).data(), stream.samples.col(c).data() + samples);
    std::erase_if(values, [](float value) { return !std::isfinite(value); });
    if (values.empty()) continue;
    rest[static_cast<size_t>(c)] = tactile::stats::median(values);
    for (float value : values) range = std::max(range, value - rest[static_cast<size_t>(c)]);
  }
  const float on = 40.0f / 255.0f * range;
  const int needed = std::min(3, std::max(1, (channels + 7) / 8));
  std::vector<uint8_t> touching(static_cast<size_t>(samples), 0);
  for (int64_t t = 0; t < samples; ++t) {
    int count = 0;
    for (int c = 0; c < channels; ++c)
      count += stream.samples(t, c) - rest[static_cast<size_t>(c)] > on;
    touching[static_cast<size_t>(t)] = on > 0 && count >= needed;
  }
  std::vector<uint8_t> dilated = touching;
  for (int64_t t = 0; t < samples; ++t)
    if (touching[static_cast<size_t>(t)]) {
      if (t > 0) dilated[static_cast<size_t>(t - 1)] = 1;
      if (t + 1 < samples) dilated[static_cast<size_t>(t + 1)] = 1;
    }
  std::vector<Label> labels;
  for (int64_t t = 0; t < samples; ++t) {
    if (!dilated[static_cast<size_t>(t)]) continue;
    int64_t last = t;
    while (last + 1 < samples && dilated[static_cast<size_t>(last + 1)]) ++last;
    Label label;
    label.t0 = stream.time_of(t);
    label.t1 = stream.time_of(last) + 1.0 / stream.rate_hz;
    labels.push_back(label);
    t = last;
  }
  return labels;
}

TouchScore score_of(const std::vector<Label>& found, const Labelled& item) {
  const tactile::Stream& stream = item.recording.streams.front();
  return tactile::score_touches(found, item.touches, stream.time_of(0), stream.rate_hz,
                                stream.sample_count());
}

std::string cell(const TouchScore& score) {
  char text[64];
  std::snprintf(text, sizeof text, "%.3f / %.3f (%lld)", score.frames.f1(), score.events.f1(),
                static_cast<long long>(score.segments));
  return text;
}

// adaptive fitted to the first five touches of each recording, scored on each recording's
// touches after the fifth (from the sixth's start to the last one's end). "-" when no
// recording has six.
std::string fitted_cell(const std::vector<Labelled>& items) {
  std::vector<tactile::FitRecording> five;
  for (const Labelled& item : items) {
    std::vector<Label> touches = item.touches;
    std::sort(touches.begin(), touches.end(),
              [](const Label& a, const Label& b) { return a.t0 < b.t0; });
    touches.resize(std::min<size_t>(5, touches.size()));
    five.push_back({&item.recording, &item.layout, touches});
  }
  const tactile::SegmenterFit fit = tactile::fit_segmenter(five);
  TouchScore unseen;
  bool any = false;
  for (const Labelled& item : items) {
    std::vector<Label> touches = item.touches;
    std::sort(touches.begin(), touches.end(),
              [](const Label& a, const Label& b) { return a.t0 < b.t0; });
    if (touches.size() < 6) continue;
    any = true;
    touches.erase(touches.begin(), touches.begin() + 5);
    const double from = touches.front().t0, to = touches.back().t1;
    std::vector<Label> found;
    for (const Label& segment :
         tactile::segment_recording("adaptive", item.recording, item.layout,
                                    tactile::Parameters::parse(fit.params, "fit")))
      if (segment.t1 > from && segment.t0 < to) found.push_back(segment);
    const tactile::Stream& stream = item.recording.streams.front();
    const auto first =
        static_cast<int64_t>(std::ceil((from - stream.time_of(0)) * stream.rate_hz - 1e-9));
    const auto end =
        static_cast<int64_t>(std::ceil((to - stream.time_of(0)) * stream.rate_hz - 1e-9));
    unseen += tactile::score_touches(found, touches, stream.time_of(0) + first / stream.rate_hz,
                                     stream.rate_hz, end - first);
  }
  if (!any) return "-";
  return cell(unseen) + " `" + fit.params + "`";
}

std::string adaptive_params;  // --params: the adaptive column's parameters

void print_row(const std::string& name, const std::string& own_method,
               const std::vector<Labelled>& items, bool fit) {
  TouchScore baseline, own, adaptive;
  int64_t touches = 0;
  for (const Labelled& item : items) {
    touches += static_cast<int64_t>(item.touches.size());
    baseline += score_of(baseline_touches(item.recording), item);
    const auto [method, params] = tactile::default_segmenter(item.layout.id);
    std::vector<Label> own_found;
    try {
      own_found = tactile::segment_recording(method, item.recording, item.layout,
                                             tactile::Parameters::parse(params, item.layout.id));
    } catch (const tactile::Error&) {
      // The skin's own segmenter may need what a faulty recording lacks.
    }
    own += score_of(own_found, item);
    adaptive += score_of(
        tactile::segment_recording("adaptive", item.recording, item.layout,
                                   tactile::Parameters::parse(adaptive_params, "--params")),
        item);
  }
  std::printf("| %s | %lld | %s | %s | %s | %s |\n", name.c_str(), static_cast<long long>(touches),
              cell(baseline).c_str(), (own_method + ": " + cell(own)).c_str(),
              cell(adaptive).c_str(), fit ? fitted_cell(items).c_str() : "-");
  std::fflush(stdout);
}

// A recording of `layout_id` at `rate` Hz with value(t, channel), and its touches [first, end)
// in frames.
Labelled made(const std::string& layout_id, double rate, int samples,
              const std::function<float(int, int)>& value,
              const std::vector<std::pair<int, int>>& touches) {
  Labelled item;
  item.layout = tactile::load_layout(layout_id);
  item.recording.id = "made";
  item.recording.layout_id = layout_id;
  tactile::Stream stream;
  stream.name = "skin";
  stream.rate_hz = rate;
  for (const tactile::Channel& channel : item.layout.channels)
    stream.channels.push_back(channel.name);
  stream.samples.resize(samples, static_cast<Eigen::Index>(stream.channels.size()));
  for (int t = 0; t < samples; ++t)
    for (Eigen::Index c = 0; c < stream.samples.cols(); ++c)
      stream.samples(t, c) = value(t, static_cast<int>(c));
  item.recording.streams = {stream};
  for (const auto& [first, end] : touches) {
    Label label;
    label.t0 = first / rate;
    label.t1 = end / rate;
    item.touches.push_back(label);
  }
  return item;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    int subjects = 3;
    uint64_t seed = 1;
    std::string fault_spec = "realistic";
    std::string dev;
    bool simulated = true;
    std::vector<std::string> skins;
    for (int k = 1; k < argc; ++k) {
      const std::string word = argv[k];
      if (word == "--subjects" && k + 1 < argc)
        subjects = std::atoi(argv[++k]);
      else if (word == "--faults" && k + 1 < argc)
        fault_spec = argv[++k];
      else if (word == "--seed" && k + 1 < argc)
        seed = std::strtoull(argv[++k], nullptr, 10);
      else if (word == "--params" && k + 1 < argc)
        adaptive_params = argv[++k];
      else if (word == "--dev" && k + 1 < argc)
        dev = argv[++k];
      else if (word == "--no-sim")
        simulated = false;
      else
        skins.push_back(word);
    }
    if (skins.empty() && simulated) {
      skins = tactile::simulated_skin_ids();
      skins.push_back("grid:16x16");
      skins.push_back("grid:19x27");
    }
    std::printf(
        "segment_bench: each cell frame F1 / event F1 (segments); fitted: on the touches after "
        "the fifth of each recording, with the parameters chosen on the first five\n\n");
    std::printf(
        "| data | touches | baseline | the skin's own segmenter | adaptive | adaptive fitted to 5 "
        "touches per recording |\n|---|---|---|---|---|---|\n");
    if (!dev.empty()) {
      std::vector<Labelled> items;
      tactile::LabelStore store((std::filesystem::path(dev) / "labels.db").string(),
                                tactile::LabelStore::OpenMode::kReadOnly);
      std::vector<std::filesystem::path> files;
      for (const auto& entry : std::filesystem::directory_iterator(dev))
        if (entry.path().extension() == ".h5") files.push_back(entry.path());
      std::sort(files.begin(), files.end());
      for (const auto& file : files) {
        Labelled item;
        item.recording = tactile::read_recording(file.string());
        item.layout = tactile::load_layout(item.recording.layout_id);
        tactile::LabelFilter filter;
        filter.recording = item.recording.id;
        filter.source = tactile::LabelSource::kGroundTruth;
        item.touches = store.list(filter);
        items.push_back(std::move(item));
      }
      print_row("development set (" + std::to_string(items.size()) + " recordings)", "adaptive",
                items, true);
    }
    {
      // Clean pulses (issue 40): channel i = max(0, sin(t / 7)) x (i mod 5), 50 Hz, 10 s.
      std::vector<std::pair<int, int>> halves;
      for (int k = 0; 44 * k < 500; ++k)
        halves.emplace_back(static_cast<int>(std::ceil(2 * M_PI * 7 * k)),
                            std::min(500, static_cast<int>(std::ceil(M_PI * 7 * (2 * k + 1)))));
      print_row("clean pulses, grid:4x4", "adaptive",
                {made(
                    "grid:4x4", 50.0, 500,
                    [](int t, int c) {
                      return static_cast<float>(std::max(0.0, std::sin(t / 7.0)) * (c % 5));
                    },
                    halves)},
                true);
      // A binary 0/1 strip at 50 Hz: 20 touches of 0.4-1.2 s, each with a 2-frame lift in it.
      std::vector<std::pair<int, int>> touches;
      for (int k = 0; k < 20; ++k)
        touches.emplace_back(100 + 120 * k, 100 + 120 * k + 20 + 10 * (k % 5));
      print_row("binary 0/1, strip:8", "adaptive",
                {made(
                    "strip:8", 50.0, 100 + 120 * 20,
                    [&](int t, int c) {
                      for (int k = 0; k < 20; ++k) {
                        const auto [first, end] = touches[static_cast<size_t>(k)];
                        const int middle = (first + end) / 2;
                        if (t >= first && t < end && !(t >= middle && t < middle + 2) &&
                            (c == k % 8 || c == (k + 3) % 8))
                          return 1.0f;
                      }
                      return 0.0f;
                    },
                    touches)},
                true);
      // A saturating 8-bit grid at 15 Hz: idle levels 0-40, noise of a count, 20 presses of
      // 1 s clipped at 255, crosstalk of 30 counts elsewhere.
      std::mt19937 random(4);
      std::uniform_int_distribution<int> noise(-1, 1);
      std::vector<std::pair<int, int>> presses;
      for (int k = 0; k < 20; ++k) presses.emplace_back(30 + 45 * k, 45 + 45 * k);
      print_row("saturating 8-bit, grid:4x4", "adaptive",
                {made(
                    "grid:4x4", 15.0, 30 + 45 * 20 + 30,
                    [&](int t, int c) {
                      const int row = c / 4, column = c % 4, local = t - 30;
                      double value = (c * 7) % 41 + noise(random);
                      if (local >= 0 && local % 45 < 15 && local / 45 < 20)
                        value += row >= 1 && row <= 2 && column >= (local / 45) % 3 &&
                                         column <= (local / 45) % 3 + 1
                                     ? 400.0
                                     : 30.0;
                      return static_cast<float>(std::clamp(std::round(value), 0.0, 255.0));
                    },
                    presses)},
                true);
    }
    for (const std::string& skin : skins) {
      // A grid:RxC is no registered skin: the pressure grid's simulator, adaptive its own.
      const bool grid = tactile::find_skin(skin) == nullptr && skin.rfind("grid:", 0) == 0;
      const tactile::SkinLayout layout = tactile::load_layout(skin);
      for (const std::string& faults : {std::string("none"), fault_spec}) {
        tactile::SimulationOptions options;
        options.seed = seed;
        options.subjects = subjects;
        options.faults = faults;
        std::vector<Labelled> items;
        for (int subject = 0; subject < subjects; ++subject) {
          tactile::SimulatedTrial trial =
              grid ? tactile::simulate_grid_trial(layout, options, subject, 0)
                   : tactile::skin_record(skin).simulate(layout, options, subject, 0);
          tactile::apply_sensor_faults(trial, layout,
                                       tactile::parse_sensor_faults(options.faults, "faults"),
                                       options.seed, subject, 0);
          items.push_back({std::move(trial.recording), layout, std::move(trial.labels)});
        }
        print_row(skin + ", faults " + faults, tactile::default_segmenter(skin).first, items, true);
      }
    }
  } catch (const std::exception& error) {
    std::fprintf(stderr, "segment_bench: %s\n", error.what());
    return 1;
  }
  return 0;
}
