#include "tactile/video/video_player.h"

#include <algorithm>
#include <exception>
#include <utility>

namespace tactile {

VideoPlayer::VideoPlayer(std::string path, VideoOpenOptions options)
    : worker_([this, path = std::move(path), options] { run(path, options); }) {}

VideoPlayer::~VideoPlayer() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  worker_.join();
}

void VideoPlayer::want(double video_time, bool playing) {
  {
    std::lock_guard lock(mutex_);
    if (want_set_ && want_time_ == video_time && playing_ == playing) return;
    want_time_ = video_time;
    want_set_ = true;
    playing_ = playing;
    if (times_) {
      // The frame index is known at once, so that `wanted` and the state say it this frame.
      const std::vector<double>& times = *times_;
      const auto after = std::upper_bound(times.begin(), times.end(), video_time);
      wanted_ = (after == times.begin() || video_time >= info_->duration)
                    ? -1
                    : static_cast<int64_t>(after - times.begin()) - 1;
      if (ahead_ && ahead_->index == wanted_) shown_ = std::exchange(ahead_, nullptr);
    }
  }
  wake_.notify_all();
}

std::shared_ptr<const VideoFrame> VideoPlayer::shown() const {
  std::lock_guard lock(mutex_);
  return shown_;
}

int64_t VideoPlayer::wanted() const {
  std::lock_guard lock(mutex_);
  return wanted_;
}

bool VideoPlayer::caught_up() const {
  std::lock_guard lock(mutex_);
  if (opening_) return false;
  if (!problem_.empty() || !want_set_) return true;
  return wanted_ < 0 ? shown_ == nullptr : shown_ && shown_->index == wanted_;
}

std::shared_ptr<const VideoInfo> VideoPlayer::info() const {
  std::lock_guard lock(mutex_);
  return info_;
}

std::shared_ptr<const std::vector<double>> VideoPlayer::frame_times() const {
  std::lock_guard lock(mutex_);
  return times_;
}

bool VideoPlayer::opening() const {
  std::lock_guard lock(mutex_);
  return opening_;
}

std::string VideoPlayer::problem() const {
  std::lock_guard lock(mutex_);
  return problem_;
}

void VideoPlayer::run(std::string path, VideoOpenOptions options) {
  std::unique_ptr<VideoFile> file;
  try {
    file = std::make_unique<VideoFile>(path, options);
  } catch (const std::exception& failure) {
    std::lock_guard lock(mutex_);
    problem_ = failure.what();
    opening_ = false;
    return;
  }
  std::unique_lock lock(mutex_);
  info_ = std::make_shared<const VideoInfo>(file->info());
  times_ = std::make_shared<const std::vector<double>>(file->frame_times());
  opening_ = false;
  if (want_set_) wanted_ = file->frame_index_at(want_time_);
  int64_t read_ahead = -1;  // the frame after the shown one, decoded into the file's cache
  while (!stop_) {
    if (!want_set_) {
      wake_.wait(lock);
      continue;
    }
    const int64_t index = file->frame_index_at(want_time_);
    wanted_ = index;
    const int64_t shown = shown_ ? shown_->index : -1;
    if (index < 0) {
      shown_.reset();
    } else if (index != shown) {
      lock.unlock();
      std::shared_ptr<const VideoFrame> frame;
      std::string failure;
      try {
        frame = std::make_shared<const VideoFrame>(file->frame(index));
      } catch (const std::exception& error) {
        failure = error.what();
      }
      lock.lock();
      if (!failure.empty()) {
        problem_ = failure;
        want_set_ = false;  // a corrupt frame is not asked for again until the time moves
        continue;
      }
      problem_.clear();
      shown_ = std::move(frame);
      continue;  // the wanted time may have moved while decoding
    } else if (playing_ && index + 1 < static_cast<int64_t>(file->frame_times().size()) &&
               read_ahead != index + 1) {
      read_ahead = index + 1;
      lock.unlock();
      std::shared_ptr<const VideoFrame> next;
      try {
        next = std::make_shared<const VideoFrame>(file->frame(read_ahead));
      } catch (const std::exception&) {
        // Named when it is shown.
      }
      lock.lock();
      ahead_ = std::move(next);
      continue;
    }
    wake_.wait(lock);
  }
}

}  // namespace tactile
