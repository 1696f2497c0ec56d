#include "ring_skin.h"

#include <cmath>
#include <numbers>
#include <random>

#include "tactile/features/feature_extractor.h"
#include "tactile/skins/skin.h"
#include "tactile/text.h"

namespace tactile::test {

namespace {

constexpr int kRingTaxels = 12;
constexpr double kRingRate = 50.0;
constexpr double kRingRadius = 40.0;  // mm

//---- Simulator: rest at 100 counts with noise; a press raises three neighbours for 0.8 s, a
// swipe runs a bump once around the ring in 1.2 s.

double ring_bump(double distance) { return std::exp(-distance * distance / 0.8); }

// Distance between two taxels around the ring, in taxels.
double ring_distance(double a, double b) {
  const double d = std::fmod(std::abs(a - b), kRingTaxels);
  return std::min(d, kRingTaxels - d);
}

SimulatedTrial simulate_ring_trial(const SkinLayout& layout, const SimulationOptions& options,
                                   int subject, int trial) {
  std::mt19937_64 random = derive_engine(options.seed, "ring", subject, trial);
  std::uniform_real_distribution<double> place(0.0, kRingTaxels);
  std::normal_distribution<double> noise(0.0, 1.5);
  const int repetitions = options.repetitions > 0 ? options.repetitions : 4;
  const double gap = 1.5, press_seconds = 0.8, swipe_seconds = 1.2;
  const int touches = 2 * repetitions;
  const double duration = gap + touches * (gap + swipe_seconds);
  const auto samples = static_cast<Eigen::Index>(duration * kRingRate);

  SimulatedTrial result;
  Recording& recording = result.recording;
  recording.id = simulated_recording_id(kRingSkin, subject, trial);
  recording.layout_id = layout.id;
  recording.metadata = {{"skin", kRingSkin},
                        {"subject", std::to_string(subject + 1)},
                        {"trial", std::to_string(trial + 1)}};
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = kRingRate;
  for (const Channel& channel : layout.channels) {
    stream.channels.push_back(channel.name);
    stream.units.push_back(channel.unit);
  }
  stream.samples.resize(samples, kRingTaxels);
  for (Eigen::Index row = 0; row < samples; ++row)
    for (int taxel = 0; taxel < kRingTaxels; ++taxel)
      stream.samples(row, taxel) = static_cast<float>(100.0 + noise(random));

  double t = gap;
  for (int touch = 0; touch < touches; ++touch) {
    const bool swipe = touch % 2 == 1;
    const double seconds = swipe ? swipe_seconds : press_seconds;
    const double start = place(random);
    const auto first = static_cast<Eigen::Index>(t * kRingRate);
    const auto last = static_cast<Eigen::Index>((t + seconds) * kRingRate);
    for (Eigen::Index row = first; row < last && row < samples; ++row) {
      const double progress = static_cast<double>(row - first) / static_cast<double>(last - first);
      const double centre = swipe ? start + progress * kRingTaxels : start;
      for (int taxel = 0; taxel < kRingTaxels; ++taxel)
        stream.samples(row, taxel) +=
            static_cast<float>(400.0 * ring_bump(ring_distance(taxel, centre)));
    }
    Label label;
    label.recording = recording.id;
    label.t0 = t;
    label.t1 = t + seconds;
    label.class_name = swipe ? "swipe" : "press";
    label.annotator = "simulator";
    label.source = LabelSource::kGroundTruth;
    result.labels.push_back(label);
    t += seconds + gap;
  }
  recording.streams.push_back(std::move(stream));
  return result;
}

//---- Pipeline: how far the pressed place travels, and how hard and wide the touch is.

class RingMotion final : public FeatureExtractor {
 public:
  std::string name() const override { return "ring_motion"; }
  std::string description() const override { return "travel, peak and width of a touch on a ring"; }
  std::vector<FeatureColumn> columns(const SkinLayout&) const override {
    return {{"travel", "taxels the strongest taxel moves over, summed around the ring"},
            {"peak", "largest rise over the segment's first sample (counts)"},
            {"width", "taxels above half the peak, at the peak"}};
  }
  FeatureResult extract(const SegmentInput& input) const override {
    const Stream& stream = input.recording.streams.front();
    const Eigen::Index first = stream.index_at(input.segment.t0);
    const Eigen::Index last = stream.index_at(input.segment.t1);
    if (last - first < 3) return FeatureResult::skip("shorter than three samples");
    const Eigen::MatrixXd values = stream.samples.middleRows(first, last - first).cast<double>();
    const Eigen::RowVectorXd rest = values.colwise().minCoeff();
    const Eigen::MatrixXd rise = values.rowwise() - rest;
    Eigen::Index peak_row = 0, peak_taxel = 0;
    const double peak = rise.maxCoeff(&peak_row, &peak_taxel);
    double travel = 0.0;
    Eigen::Index previous = -1;
    for (Eigen::Index row = 0; row < rise.rows(); ++row) {
      Eigen::Index strongest = 0;
      if (rise.row(row).maxCoeff(&strongest) < 0.5 * peak) continue;
      if (previous >= 0)
        travel += ring_distance(static_cast<double>(strongest), static_cast<double>(previous));
      previous = strongest;
    }
    const double width = static_cast<double>((rise.row(peak_row).array() > 0.5 * peak).count());
    return {{travel, peak, width}, ""};
  }
};

}  // namespace

std::string ring_layout_json() {
  std::string taxels, channels;
  for (int k = 0; k < kRingTaxels; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / kRingTaxels;
    const std::string name = "p" + std::to_string(k);
    channels += std::string(k ? "," : "") + R"({"name": ")" + name +
                R"(", "unit": "counts", "modality": "pressure"})";
    taxels += std::string(k ? "," : "") + R"({"id": )" + std::to_string(k) + R"(, "x": )" +
              shortest_text(kRingRadius * std::cos(angle)) + R"(, "y": )" +
              shortest_text(kRingRadius * std::sin(angle)) +
              R"(, "w": 16, "h": 16, "area": 201, "shape": "circle", "channels": {"pressure": ")" +
              name + R"("}})";
  }
  return R"({"id": "ring", "name": "Ring of 12 pressure taxels", "sample_rate_hz": 50,
  "modalities": ["pressure"], "display": {"modality": "pressure", "min": 100, "max": 400},
  "channels": [)" +
         channels + R"(], "taxels": [)" + taxels + R"(], "classes": ["press", "swipe"]})";
}

void register_ring_skin() {
  register_feature_pipeline("ring_motion",
                            [](const Parameters&) { return std::make_unique<RingMotion>(); });
  SkinRecord ring;
  ring.id = kRingSkin;
  ring.name = "a ring of 12 pressure taxels (a test's own skin)";
  ring.layout = parse_layout_json(ring_layout_json(), "ring layout");
  ring.simulate = simulate_ring_trial;
  ring.pipeline = "ring_motion";
  ring.segmenter = "adaptive";
  register_skin(std::move(ring));
}

}  // namespace tactile::test
