#include "clip.h"

#include <algorithm>
#include <cmath>

#include "tactile/error.h"
#include "tactile/text.h"
#include "tactile/video/video_writer.h"
#include "video.h"

namespace tactile {

namespace {

// Frames drawn at one time waiting for a video's decoder before the frame is written as it is
// (a video that cannot be read says so in its place).
constexpr int kMostFramesWaited = 600;

}  // namespace

ClipRecorder::ClipRecorder(ClipRequest request) : request_(std::move(request)) {}
ClipRecorder::~ClipRecorder() = default;

double ClipRecorder::before_frame(Workbench& workbench) {
  WorkbenchState& state = workbench.state();
  if (done_) return 0.0;
  if (!started_) {
    started_ = true;
    if (!state.document) {
      error_ = "clip: no recording open" + (state.error.empty() ? "" : ": " + state.error);
      done_ = true;
      return 0.0;
    }
    const std::vector<Label>& labels = state.document->labels;
    auto found = std::find_if(labels.begin(), labels.end(),
                              [&](const Label& label) { return label.id == request_.label; });
    if (found == labels.end()) {
      error_ = "clip: " + state.document->path + " has no label " + std::to_string(request_.label) +
               " (tactile labels list shows their ids)";
      done_ = true;
      return 0.0;
    }
    const std::vector<VideoState::Shown>& videos = state.video.videos;
    if (!request_.video.empty() &&
        std::none_of(videos.begin(), videos.end(), [&](const VideoState::Shown& shown) {
          return shown.attachment.name == request_.video;
        })) {
      error_ = "clip: the recording has no video " + in_quotes(request_.video) +
               " (tactile video list shows them)";
      done_ = true;
      return 0.0;
    }
    const SampleSource& source = state.document->samples();
    start_ = std::max(source.start_time(), found->t0 - request_.margin);
    end_ = std::min(source.end_time(), found->t1 + request_.margin);
    state.selection.labels = {found->id};
    state.plot.view_t0 = start_;
    state.plot.view_t1 = std::max(end_, start_ + 1e-3);
    state.plot.fitted = true;
  }
  state.clock.pause();
  state.clock.seek(start_ + static_cast<double>(written_) / request_.rate);
  return 0.0;
}

void ClipRecorder::after_frame(Workbench& workbench, const std::function<const Image&()>& image) {
  if (done_) return;
  WorkbenchState& state = workbench.state();
  if (!videos_caught_up(state) && ++waited_ < kMostFramesWaited) return;
  waited_ = 0;
  try {
    const Image& frame = image();
    // The encoders' 4:2:0 chroma wants even sizes: the last odd row or column is left out.
    const int width = frame.width & ~1, height = frame.height & ~1;
    if (!writer_) {
      VideoWriterOptions options;
      options.width = width;
      options.height = height;
      options.rate = request_.rate;
      writer_ = std::make_unique<VideoWriter>(request_.out, options);
    }
    if (width == frame.width && height == frame.height) {
      writer_->write(frame.rgba.data(), static_cast<double>(written_) / request_.rate);
    } else {
      const Image even = frame.crop(0, 0, width, height);
      writer_->write(even.rgba.data(), static_cast<double>(written_) / request_.rate);
    }
    ++written_;
    if (start_ + static_cast<double>(written_) / request_.rate > end_) {
      writer_->finish();
      done_ = true;
    }
  } catch (const Error& failure) {
    error_ = failure.what();
    done_ = true;
  }
}

}  // namespace tactile
