#include "tactile/video/video_writer.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "ffmpeg_handles.h"
#include "tactile/error.h"
#include "tactile/text.h"

namespace tactile {

using namespace video_detail;

namespace {

std::string lower_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

// The encoder for a file's extension when none is asked for (video_writer.h).
std::string encoder_for(const std::string& path) {
  const std::string extension = lower_extension(path);
  if (extension == ".avi") return "mjpeg";
  if (extension == ".webm") return "libvpx-vp9";
  if (avcodec_find_encoder_by_name("libx264")) return "libx264";
  return "mpeg4";
}

}  // namespace

struct VideoWriter::Impl {
  std::string path;
  VideoWriterOptions options;
  std::string codec_name;
  OutputContext format;
  CodecContext encoder;
  Frame picture = Frame(av_frame_alloc());
  Packet packet = Packet(av_packet_alloc());
  ScaleContext scale;
  AVStream* stream = nullptr;
  int64_t last_pts = AV_NOPTS_VALUE;
  double last_time = 0;
  bool header_written = false;
  bool finished = false;

  void open();
  void write(const uint8_t* rgba, double time);
  void send(const AVFrame* frame);
  void finish();
  [[noreturn]] void fail(const std::string& message) const { throw Error(path, message); }
};

void VideoWriter::Impl::open() {
  keep_ffmpeg_quiet();
  if (options.width <= 0 || options.height <= 0 || options.width % 2 || options.height % 2)
    fail(
        "the frame size must be positive even numbers (the encoders' 4:2:0 colour needs them), "
        "not " +
        std::to_string(options.width) + "x" + std::to_string(options.height));
  if (!(options.rate > 0) || !std::isfinite(options.rate))
    fail("the frame rate must be a positive number, not " + shortest_text(options.rate));

  AVFormatContext* raw = nullptr;
  avformat_alloc_output_context2(&raw, nullptr, nullptr, path.c_str());
  if (!raw)
    fail("no video container is known for the extension " + in_quotes(lower_extension(path)) +
         " (use .mp4, .mkv, .mov, .avi or .webm)");
  format.reset(raw);

  codec_name = options.codec.empty() ? encoder_for(path) : options.codec;
  const AVCodec* codec = avcodec_find_encoder_by_name(codec_name.c_str());
  if (!codec || codec->type != AVMEDIA_TYPE_VIDEO)
    fail("this FFmpeg has no video encoder " + in_quotes(codec_name));
  stream = avformat_new_stream(format.get(), nullptr);
  encoder.reset(avcodec_alloc_context3(codec));
  if (!stream || !encoder) fail("out of memory for the encoder");

  // Each frame keeps its own time: 1/(rate*100) s resolves any time a clock gives to 1 % of a
  // frame. AVI has no time stamps, only a frame count at a fixed rate: there a frame is one unit.
  const bool fixed_rate = std::string(format->oformat->name) == "avi";
  const int ticks = static_cast<int>(std::lround(options.rate * (fixed_rate ? 1 : 100)));
  encoder->time_base = AVRational{1, std::max(ticks, 1)};
  encoder->framerate = av_d2q(options.rate, 100000);
  encoder->width = options.width;
  encoder->height = options.height;
  encoder->pix_fmt = codec->pix_fmts ? codec->pix_fmts[0] : AV_PIX_FMT_YUV420P;
  encoder->gop_size = std::max(1, static_cast<int>(std::lround(options.rate * 2)));
  encoder->thread_count = 2;
  if (format->oformat->flags & AVFMT_GLOBALHEADER) encoder->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;

  const int quality = std::clamp(options.quality, 0, 63);
  if (codec_name == "libx264" || codec_name == "libx265") {
    av_opt_set(encoder->priv_data, "crf", std::to_string(quality).c_str(), 0);
    av_opt_set(encoder->priv_data, "preset", "veryfast", 0);
  } else if (codec_name == "libvpx-vp9" || codec_name == "libvpx") {
    av_opt_set(encoder->priv_data, "crf", std::to_string(std::clamp(quality + 8, 0, 63)).c_str(),
               0);
    av_opt_set(encoder->priv_data, "deadline", "realtime", 0);
    av_opt_set(encoder->priv_data, "cpu-used", "8", 0);
    encoder->bit_rate = 0;
  } else {
    // MJPEG, MPEG-4 part 2: a fixed quantiser, 2 (best) to 31; the default 23 gives 3.
    encoder->flags |= AV_CODEC_FLAG_QSCALE;
    encoder->global_quality = FF_QP2LAMBDA * std::clamp(quality / 7, 2, 31);
  }

  int code = avcodec_open2(encoder.get(), codec, nullptr);
  if (code < 0)
    fail("cannot open the encoder " + in_quotes(codec_name) + ": " + av_error_text(code));
  code = avcodec_parameters_from_context(stream->codecpar, encoder.get());
  if (code < 0) fail("cannot set up the video stream: " + av_error_text(code));
  stream->time_base = encoder->time_base;
  stream->avg_frame_rate = encoder->framerate;

  if (!(format->oformat->flags & AVFMT_NOFILE)) {
    code = avio_open(&format->pb, path.c_str(), AVIO_FLAG_WRITE);
    if (code < 0) fail("cannot create the file: " + av_error_text(code));
  }
  code = avformat_write_header(format.get(), nullptr);
  if (code < 0) fail("cannot write the file's header: " + av_error_text(code));
  header_written = true;

  picture->format = encoder->pix_fmt;
  picture->width = options.width;
  picture->height = options.height;
  code = av_frame_get_buffer(picture.get(), 0);
  if (code < 0) fail("out of memory for a frame: " + av_error_text(code));
  scale.reset(sws_getContext(options.width, options.height, AV_PIX_FMT_RGBA, options.width,
                             options.height, encoder->pix_fmt, SWS_BILINEAR, nullptr, nullptr,
                             nullptr));
  if (!scale) fail("cannot convert RGBA frames for the encoder " + in_quotes(codec_name));
}

// Gives the encoder a frame (nullptr: the end) and writes every packet it has ready.
void VideoWriter::Impl::send(const AVFrame* frame) {
  int code = avcodec_send_frame(encoder.get(), frame);
  if (code < 0) fail("the encoder refused a frame: " + av_error_text(code));
  while (true) {
    code = avcodec_receive_packet(encoder.get(), packet.get());
    if (code == AVERROR(EAGAIN) || code == AVERROR_EOF) return;
    if (code < 0) fail("the encoder failed: " + av_error_text(code));
    av_packet_rescale_ts(packet.get(), encoder->time_base, stream->time_base);
    packet->stream_index = stream->index;
    code = av_interleaved_write_frame(format.get(), packet.get());
    if (code < 0) fail("cannot write a frame: " + av_error_text(code));
  }
}

void VideoWriter::Impl::write(const uint8_t* rgba, double time) {
  if (finished) fail("the video is already finished");
  const int64_t stamp = std::llround(time / av_q2d(encoder->time_base));
  if (!std::isfinite(time) || (last_pts != AV_NOPTS_VALUE && stamp <= last_pts)) {
    std::string message = "the frame time " + seconds_text(time) + " s does not come after the ";
    message += "previous frame's " + seconds_text(last_time) + " s";
    if (last_pts != AV_NOPTS_VALUE && time > last_time)
      message += " by one unit of the stream's time base (1/" +
                 std::to_string(encoder->time_base.den) + " s)";
    fail(message);
  }
  int code = av_frame_make_writable(picture.get());
  if (code < 0) fail("out of memory for a frame: " + av_error_text(code));
  const uint8_t* planes[4] = {rgba, nullptr, nullptr, nullptr};
  const int strides[4] = {options.width * 4, 0, 0, 0};
  sws_scale(scale.get(), planes, strides, 0, options.height, picture->data, picture->linesize);
  picture->pts = stamp;
  send(picture.get());
  last_pts = stamp;
  last_time = time;
}

void VideoWriter::Impl::finish() {
  if (finished) return;
  finished = true;
  send(nullptr);
  const int code = av_write_trailer(format.get());
  if (code < 0) fail("cannot finish the file: " + av_error_text(code));
  if (!(format->oformat->flags & AVFMT_NOFILE)) avio_closep(&format->pb);
}

VideoWriter::VideoWriter(const std::string& path, VideoWriterOptions options)
    : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  impl_->options = std::move(options);
  try {
    impl_->open();
  } catch (...) {
    // Nothing half made is left behind.
    const bool created = impl_->format && impl_->format->pb;
    impl_.reset();
    std::error_code ignored;
    if (created) std::filesystem::remove(path, ignored);
    throw;
  }
}

VideoWriter::~VideoWriter() {
  if (!impl_ || impl_->finished) return;
  try {
    impl_->finish();
  } catch (...) {
    // The destructor finishes quietly: finish() is where a caller hears of a failure.
  }
}

void VideoWriter::write(const uint8_t* rgba, double time) { impl_->write(rgba, time); }
void VideoWriter::finish() { impl_->finish(); }
const std::string& VideoWriter::codec() const { return impl_->codec_name; }

}  // namespace tactile
