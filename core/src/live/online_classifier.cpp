#include "tactile/live/online_classifier.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "tactile/error.h"
#include "tactile/segment/segmenter.h"

namespace tactile {

OnlineClassifier::OnlineClassifier(SavedModel model, SkinLayout layout, const SourceInfo& stream,
                                   OnlineOptions options)
    : model_(std::move(model)),
      layout_(std::move(layout)),
      options_(std::move(options)),
      segmenter_params_(Parameters::parse(options_.segmenter_params, "segmenter parameters")),
      rate_(stream.rate_hz) {
  if (model_.pipeline.empty())
    throw Error("online model", "does not say which feature pipeline made its features");
  if (!model_.layout.empty() && model_.layout != layout_.id)
    throw Error("online model",
                "is for skin '" + model_.layout + "', the stream is '" + layout_.id + "'");
  if (!(options_.hop_seconds > 0.0) || !(options_.window_seconds > 0.0) ||
      !(options_.lookback_seconds >= options_.window_seconds))
    throw Error("online classification",
                "window and hop must be positive and the lookback at least the window");
  // A touch is over once a few samples after it are quiet, however fast the skin.
  options_.release_seconds = std::max(options_.release_seconds, 3.0 / rate_);
  const std::vector<std::string> methods = segmenter_methods();
  if (std::find(methods.begin(), methods.end(), options_.segmenter) == methods.end())
    throw Error("online classification", "no segmenter '" + options_.segmenter + "'");
  thread_ = std::thread([this] { run(); });
}

OnlineClassifier::~OnlineClassifier() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

bool OnlineClassifier::in_touch() const {
  std::lock_guard lock(mutex_);
  return in_touch_;
}

void OnlineClassifier::wait_idle() {
  std::unique_lock lock(mutex_);
  idle_.wait(lock, [this] { return !working_ && !pending_.has_value(); });
}

std::string OnlineClassifier::error() const {
  std::lock_guard lock(mutex_);
  return error_;
}

std::vector<OnlineDecision> OnlineClassifier::take() {
  std::lock_guard lock(mutex_);
  return std::exchange(done_, {});
}

void OnlineClassifier::update(const LiveSampleSource& source) {
  const int64_t count = source.sample_count();
  const int64_t hop = std::max<int64_t>(1, std::llround(options_.hop_seconds * rate_));
  if (next_hop_ < 0) next_hop_ = count + hop;
  if (count < next_hop_) return;
  next_hop_ = count + hop;
  const int64_t lookback = std::llround(options_.lookback_seconds * rate_);
  const int64_t first = std::max(source.first_kept(), count - lookback);
  if (count - first < 2) return;
  Job job;
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = rate_;
  stream.start_time = source.time_of(first);
  stream.channels = source.info().channels;
  stream.units = source.info().units;
  stream.samples = source.read_all_channels(first, count - first);
  // A lost packet is held at the value before it: segmenters and pipelines expect numbers.
  for (Eigen::Index column = 0; column < stream.samples.cols(); ++column) {
    float last = 0.0f;
    bool seen = false;
    for (Eigen::Index row = 0; row < stream.samples.rows(); ++row) {
      float& value = stream.samples(row, column);
      if (std::isfinite(value)) {
        last = value;
        seen = true;
      } else {
        value = seen ? last : 0.0f;
      }
    }
  }
  job.now = source.time_of(count - 1);
  job.window.id = "live";
  job.window.layout_id = layout_.id;
  job.window.metadata = source.info().metadata;  // a device's calibration, when known
  for (const auto& [key, value] : model_.recording_metadata)
    job.window.metadata.emplace(key, value);
  job.window.streams.push_back(std::move(stream));
  {
    std::lock_guard lock(mutex_);
    pending_ = std::move(job);  // a hop still waiting is stale: replaced
  }
  wake_.notify_one();
}

void OnlineClassifier::classify(const Job& job, double t0, double t1, const std::string& region,
                                bool final) {
  const auto started = std::chrono::steady_clock::now();
  OnlineDecision decision;
  decision.t0 = t0;
  decision.t1 = t1;
  decision.final = final;
  std::string failure;
  Label segment;
  segment.recording = job.window.id;
  segment.t0 = t0;
  segment.t1 = t1;
  segment.region = region;
  segment.class_name = kUnknownClass;
  try {
    const Predictions predictions = predict_segments(model_, job.window, layout_, {segment});
    if (predictions.labels.empty()) {
      decision.class_name = kUnknownClass;
      if (!predictions.skipped.empty()) failure = predictions.skipped.front().reason;
    } else {
      decision.class_name = predictions.labels.front().class_name;
      decision.score = predictions.labels.front().confidence;
    }
  } catch (const std::exception& error) {
    decision.class_name = kUnknownClass;
    failure = error.what();
  }
  decision.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::lock_guard lock(mutex_);
  if (!failure.empty()) error_ = failure;
  done_.push_back(std::move(decision));
}

void OnlineClassifier::decide(const Job& job) {
  std::vector<Label> touches;
  try {
    touches = segment_recording(options_.segmenter, job.window, layout_, segmenter_params_);
  } catch (const std::exception& error) {
    std::lock_guard lock(mutex_);
    error_ = std::string("segmenter ") + options_.segmenter + ": " + error.what();
    // The skin's own segmenter needs what this stream lacks: the one for uncalibrated skins.
    if (options_.segmenter != "adaptive") {
      options_.segmenter = "adaptive";
      segmenter_params_ = Parameters{};
      error_ += "; segmenting with adaptive instead";
    }
    return;
  }
  std::sort(touches.begin(), touches.end(),
            [](const Label& a, const Label& b) { return a.t0 < b.t0; });
  const double hop_start = std::max(last_now_, job.now - options_.hop_seconds);
  bool open = false, touched = false;
  for (const Label& touch : touches) {
    touched = touched || touch.t1 >= hop_start;
    if (touch.t1 <= job.now - options_.release_seconds) {
      // Ended: decided once (segmented again later, its bounds may move a little).
      if (touch.t0 > decided_until_) {
        classify(job, touch.t0, touch.t1, touch.region, true);
        decided_until_ = touch.t1;
      }
    } else {
      open = true;
      const double t0 = std::max(touch.t0, job.now - options_.window_seconds);
      // A touch that has just begun has too little to tell yet.
      if (job.now - t0 >= 2.0 / rate_) classify(job, t0, job.now, touch.region, false);
    }
  }
  if (!touched && !open) {
    OnlineDecision decision;
    decision.t0 = hop_start;
    decision.t1 = job.now;
    decision.class_name = kNoTouchClass;
    decision.score = 1.0;
    std::lock_guard lock(mutex_);
    done_.push_back(std::move(decision));
  }
  last_now_ = job.now;
  std::lock_guard lock(mutex_);
  in_touch_ = open;
}

void OnlineClassifier::run() {
  for (;;) {
    Job job;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [this] { return stop_ || pending_.has_value(); });
      if (stop_) return;
      job = std::move(*pending_);
      pending_.reset();
      working_ = true;
    }
    decide(job);
    {
      std::lock_guard lock(mutex_);
      working_ = false;
    }
    idle_.notify_all();
  }
}

void add_online_decision(std::vector<Label>& lane, const OnlineDecision& decision,
                         const std::string& recording, double oldest) {
  if (decision.final)
    std::erase_if(lane, [&](const Label& label) {
      return label.note == "provisional" && label.t1 >= decision.t0 && label.t0 <= decision.t1;
    });
  Label* last = lane.empty() ? nullptr : &lane.back();
  const std::string kind = decision.final ? "final" : "provisional";
  if (last && last->class_name == decision.class_name && last->note == kind && !decision.final &&
      decision.t0 <= last->t1 + 0.5) {
    last->t1 = std::max(last->t1, decision.t1);  // the same answer goes on
    last->confidence = std::clamp(decision.score, 0.0, 1.0);
  } else {
    Label label;
    label.recording = recording;
    label.t0 = last && last->note != "final" ? std::max(decision.t0, last->t1) : decision.t0;
    label.t1 = std::max(label.t0, decision.t1);
    label.class_name = decision.class_name;
    label.annotator = kOnlineAnnotator;
    label.source = LabelSource::kModel;
    label.confidence = std::clamp(decision.score, 0.0, 1.0);
    label.note = kind;
    lane.push_back(std::move(label));
  }
  std::erase_if(lane, [&](const Label& label) { return label.t1 < oldest; });
}

}  // namespace tactile
