// The live camera: libavdevice's input read on a thread of its own, each frame scaled to RGBA,
// stamped on the live clock, kept as the newest and in the pre-trigger ring, and written while
// recording.
#include "tactile/video/camera.h"

extern "C" {
#include <libavdevice/avdevice.h>
}

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <thread>

#include "ffmpeg_handles.h"
#include "tactile/error.h"
#include "tactile/video/video_writer.h"

namespace tactile {

using namespace video_detail;

struct Camera::Impl {
  CameraOptions options;
  std::function<double()> clock;
  InputContext input;
  CodecContext decoder;
  int stream_index = -1;
  double rate = 30;  // the stream's nominal frame rate, for the writer

  std::atomic<bool> stopping{false};
  std::thread reader;

  mutable std::mutex mutex;  // guards everything below
  std::condition_variable arrived;
  std::shared_ptr<const VideoFrame> newest;  // shared with latest()'s callers, never copied
  std::deque<VideoFrame> ring;               // the last pre_trigger seconds, oldest first
  int64_t received = 0;
  std::string error;
  std::unique_ptr<VideoWriter> writer;
  std::string writer_path;
  int writer_width = 0, writer_height = 0;
  double origin = 0;  // live time of the recording's first frame

  void open();
  void read_loop();
  void deliver(VideoFrame frame);
  void fail(const std::string& message);
};

namespace {

// Stops a blocking read of the device when the camera is being closed.
int interrupted(void* opaque) { return static_cast<std::atomic<bool>*>(opaque)->load() ? 1 : 0; }

}  // namespace

void Camera::Impl::open() {
  keep_ffmpeg_quiet();
  static const bool registered = [] {
    avdevice_register_all();
    return true;
  }();
  (void)registered;
  const std::string& url = options.url;
  const size_t colon = url.find(':');
  if (colon == std::string::npos || colon == 0)
    throw Error(url, "a camera is FORMAT:INPUT, e.g. v4l2:/dev/video0");
  const std::string format_name = url.substr(0, colon);
  const std::string device = url.substr(colon + 1);
  const AVInputFormat* format = av_find_input_format(format_name.c_str());
  if (!format) throw Error(url, "this FFmpeg has no input device '" + format_name + "'");
  AVFormatContext* context = avformat_alloc_context();
  if (!context) throw Error(url, "out of memory");
  context->interrupt_callback.callback = interrupted;
  context->interrupt_callback.opaque = &stopping;
  if (const int code = avformat_open_input(&context, device.c_str(), format, nullptr); code < 0)
    throw Error(url, "cannot open: " + av_error_text(code));
  input.reset(context);
  if (const int code = avformat_find_stream_info(input.get(), nullptr); code < 0)
    throw Error(url, "cannot read its stream: " + av_error_text(code));
  const AVCodec* codec = nullptr;
  stream_index = av_find_best_stream(input.get(), AVMEDIA_TYPE_VIDEO, -1, -1, &codec, 0);
  if (stream_index < 0 || !codec) throw Error(url, "no video stream");
  const AVStream* stream = input->streams[stream_index];
  decoder.reset(avcodec_alloc_context3(codec));
  if (!decoder || avcodec_parameters_to_context(decoder.get(), stream->codecpar) < 0 ||
      avcodec_open2(decoder.get(), codec, nullptr) < 0)
    throw Error(url, std::string("cannot decode its ") + codec->name + " frames");
  const AVRational nominal =
      stream->avg_frame_rate.num > 0 ? stream->avg_frame_rate : stream->r_frame_rate;
  if (nominal.num > 0 && nominal.den > 0) rate = av_q2d(nominal);
}

void Camera::Impl::fail(const std::string& message) {
  const std::lock_guard lock(mutex);
  if (error.empty()) error = options.url + ": " + message;
  writer.reset();  // the file so far is finished by the writer's destructor
  arrived.notify_all();
}

void Camera::Impl::deliver(VideoFrame frame) {
  const std::lock_guard lock(mutex);
  frame.index = received++;
  // A frame of another size than the recording's (the device switched modes) is not written.
  if (writer && frame.width == writer_width && frame.height == writer_height)
    writer->write(frame.rgba.data(), frame.time - origin);
  ring.push_back(frame);
  while (!ring.empty() && ring.front().time < frame.time - options.pre_trigger) ring.pop_front();
  newest = std::make_shared<const VideoFrame>(std::move(frame));
  arrived.notify_all();
}

void Camera::Impl::read_loop() {
  try {
    Packet packet(av_packet_alloc());
    Frame decoded(av_frame_alloc());
    SwsContext* scale = nullptr;
    double last_stamp = -1e300;  // the stamp of the frame before
    while (!stopping.load()) {
      const int code = av_read_frame(input.get(), packet.get());
      if (code == AVERROR(EAGAIN)) {
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
        continue;
      }
      if (code < 0) {
        if (!stopping.load())
          fail(code == AVERROR_EOF ? "the stream ended" : "reading: " + av_error_text(code));
        break;
      }
      if (packet->stream_index != stream_index) {
        av_packet_unref(packet.get());
        continue;
      }
      const int sent = avcodec_send_packet(decoder.get(), packet.get());
      av_packet_unref(packet.get());
      if (sent < 0 && sent != AVERROR(EAGAIN)) {
        fail("decoding: " + av_error_text(sent));
        break;
      }
      while (avcodec_receive_frame(decoder.get(), decoded.get()) == 0) {
        // Strictly later than the frame before, by more than the writer's time base (a clock
        // that stood still, or a frame that came in with the last, would be refused there).
        const double stamp = std::max(clock(), last_stamp + 0.02 / rate);
        last_stamp = stamp;
        const int width = decoded->width, height = decoded->height;
        int out_width = std::min(width, options.max_width > 0 ? options.max_width : width);
        int out_height = static_cast<int>(
            std::lround(static_cast<double>(height) * out_width / std::max(1, width)));
        out_width = std::max(2, out_width / 2 * 2);  // the encoders' 4:2:0 chroma
        out_height = std::max(2, out_height / 2 * 2);
        scale = sws_getCachedContext(
            scale, width, height, static_cast<AVPixelFormat>(decoded->format), out_width,
            out_height, AV_PIX_FMT_RGBA, SWS_BILINEAR, nullptr, nullptr, nullptr);
        if (!scale) {
          fail("cannot convert its frames to RGBA");
          sws_freeContext(scale);
          return;
        }
        VideoFrame frame;
        frame.time = stamp;
        frame.duration = 1.0 / rate;
        frame.width = out_width;
        frame.height = out_height;
        frame.rgba.resize(static_cast<size_t>(out_width) * out_height * 4);
        uint8_t* planes[1] = {frame.rgba.data()};
        const int strides[1] = {out_width * 4};
        sws_scale(scale, decoded->data, decoded->linesize, 0, height, planes, strides);
        av_frame_unref(decoded.get());
        deliver(std::move(frame));
      }
    }
    sws_freeContext(scale);
  } catch (const std::exception& failure) {
    fail(failure.what());  // a write to the recording failed: the reader ends, the error says so
  }
}

Camera::Camera(CameraOptions options, std::function<double()> clock)
    : impl_(std::make_unique<Impl>()) {
  impl_->options = std::move(options);
  impl_->clock = std::move(clock);
  impl_->open();
  impl_->reader = std::thread([impl = impl_.get()] { impl->read_loop(); });
}

Camera::~Camera() {
  impl_->stopping.store(true);
  if (impl_->reader.joinable()) impl_->reader.join();
  const std::lock_guard lock(impl_->mutex);
  if (impl_->writer) {
    try {
      impl_->writer->finish();
    } catch (const Error&) {
      // Nothing to tell from a destructor; the file is as far as it got.
    }
  }
}

std::shared_ptr<const VideoFrame> Camera::latest() const {
  const std::lock_guard lock(impl_->mutex);
  return impl_->newest;
}

int64_t Camera::frames_received() const {
  const std::lock_guard lock(impl_->mutex);
  return impl_->received;
}

double Camera::start_recording(const std::string& path) {
  std::unique_lock lock(impl_->mutex);
  if (impl_->writer) throw Error(path, "the camera is already recording to " + impl_->writer_path);
  // The first frame gives the size: wait a little for it when the camera has just opened.
  impl_->arrived.wait_for(lock, std::chrono::seconds(5),
                          [&] { return !impl_->ring.empty() || !impl_->error.empty(); });
  if (!impl_->error.empty()) throw Error(path, "the camera stopped: " + impl_->error);
  if (impl_->ring.empty()) throw Error(path, "the camera " + impl_->options.url + " sent no frame");
  const VideoFrame& first = impl_->ring.front();
  VideoWriterOptions options;
  options.width = first.width;
  options.height = first.height;
  options.rate = impl_->rate;
  auto writer = std::make_unique<VideoWriter>(path, options);
  // The pre-trigger frames first, on their own stamps: the video's time 0 is the first.
  impl_->origin = first.time;
  for (const VideoFrame& frame : impl_->ring)
    if (frame.width == first.width && frame.height == first.height)
      writer->write(frame.rgba.data(), frame.time - impl_->origin);
  impl_->writer = std::move(writer);
  impl_->writer_path = path;
  impl_->writer_width = first.width;
  impl_->writer_height = first.height;
  return impl_->origin;
}

void Camera::stop_recording() {
  std::unique_ptr<VideoWriter> writer;
  {
    const std::lock_guard lock(impl_->mutex);
    writer = std::move(impl_->writer);
  }
  if (writer) writer->finish();
}

std::string Camera::error() const {
  const std::lock_guard lock(impl_->mutex);
  return impl_->error;
}

}  // namespace tactile
