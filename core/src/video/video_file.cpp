#include "tactile/video/video_file.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <list>
#include <system_error>

#include "ffmpeg_handles.h"
#include "tactile/error.h"
#include "tactile/text.h"

namespace tactile {

using namespace video_detail;

namespace {

// A wanted frame this close ahead of the decoder is decoded forward even across a key frame:
// a seek and the decode from the key frame would cost as much (2x play crosses key frames).
constexpr int64_t kDecodeForwardWithin = 12;

// How far back a seek may step when the demuxer lands past the wanted frame (a container whose
// index places key frames by decode time).
constexpr int kSeekAttempts = 3;

std::string frame_words(int64_t index, double time) {
  return "frame " + std::to_string(index) + " (at " + fixed_text(time, 3) + " s)";
}

}  // namespace

struct VideoFile::Impl {
  std::string path;
  VideoOpenOptions options;
  VideoInfo info;
  InputContext format;
  CodecContext decoder;
  Frame decoded = Frame(av_frame_alloc());
  Packet packet = Packet(av_packet_alloc());
  ScaleContext scale;
  int stream = -1;
  AVRational time_base{1, 1};

  std::vector<int64_t> pts;         // every frame's presentation time stamp, ascending
  std::vector<double> times;        // the same in seconds from the first
  std::vector<int64_t> key_frames;  // the indexes of the key frames, ascending
  int output_width = 0;
  int output_height = 0;

  // Where the decoder is: the last frame it gave out (-1: none since it was started again),
  // whether the end of the packets was sent (draining) and reached (finished: seek before more).
  int64_t position = -1;
  bool draining = false;
  bool finished = true;
  int64_t seeks = 0;
  int64_t decoded_frames = 0;

  std::list<VideoFrame> cache;  // most recently used first

  void open();
  void index_packets();
  void open_decoder();
  const VideoFrame& frame(int64_t index);
  // Decodes forward until frame `index`; false when the first frame after a seek lies past it.
  bool decode_until(int64_t index, VideoFrame*& result);
  void seek_to_key_frame(size_t key);
  void restart();
  int64_t index_of_pts(int64_t stamp) const;
  VideoFrame& store(int64_t index);
  [[noreturn]] void fail(const std::string& message) const { throw Error(path, message); }
};

//---- Opening and the index

void VideoFile::Impl::open() {
  keep_ffmpeg_quiet();
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (!std::filesystem::exists(status)) fail("no such file");
  if (std::filesystem::is_directory(status)) fail("is a folder, not a video file");
  if (std::filesystem::file_size(path, error) == 0 && !error) fail("the file is empty");

  AVFormatContext* raw = nullptr;
  int code = avformat_open_input(&raw, path.c_str(), nullptr, nullptr);
  if (code < 0) {
    if (code == AVERROR_INVALIDDATA)
      fail(
          "not a video FFmpeg can read (its header is damaged or missing, the file is cut short, "
          "or it is another kind of file)");
    fail("cannot open: " + av_error_text(code));
  }
  format.reset(raw);
  code = avformat_find_stream_info(format.get(), nullptr);
  if (code < 0) fail("not a video FFmpeg can read: " + av_error_text(code));
  stream = av_find_best_stream(format.get(), AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
  if (stream < 0 ||
      (format->streams[stream]->disposition & AV_DISPOSITION_ATTACHED_PIC))  // a cover image
    fail("not a video: the file holds no video stream");
  for (unsigned other = 0; other < format->nb_streams; ++other)
    if (static_cast<int>(other) != stream) format->streams[other]->discard = AVDISCARD_ALL;

  const AVStream* video = format->streams[stream];
  time_base = video->time_base;
  info.path = path;
  info.container = format->iformat->name;
  info.codec = avcodec_get_name(video->codecpar->codec_id);
  info.width = video->codecpar->width;
  info.height = video->codecpar->height;
  if (info.width <= 0 || info.height <= 0) fail("the video stream gives no frame size");

  open_decoder();
  index_packets();

  // The size frames are given at: at most max_width wide, the aspect kept, even sizes.
  output_width = info.width;
  output_height = info.height;
  if (options.max_width > 0 && options.max_width < info.width) {
    output_width = options.max_width;
    output_height =
        static_cast<int>(std::lround(static_cast<double>(info.height) * output_width / info.width));
  }
  output_width = std::max(2, output_width & ~1);
  output_height = std::max(2, 2 * static_cast<int>(std::lround(output_height / 2.0)));
  if (options.cache_frames < 1) options.cache_frames = 1;

  restart();
  try {
    frame(0);
  } catch (const Error& failure) {
    fail("no frame decodes (the file is cut short or damaged): " + failure.message());
  }
}

void VideoFile::Impl::open_decoder() {
  const AVStream* video = format->streams[stream];
  const AVCodec* codec = avcodec_find_decoder(video->codecpar->codec_id);
  if (!codec) fail("codec " + in_quotes(info.codec) + " cannot be decoded by this FFmpeg");
  decoder.reset(avcodec_alloc_context3(codec));
  if (!decoder) fail("out of memory for the decoder");
  int code = avcodec_parameters_to_context(decoder.get(), video->codecpar);
  if (code < 0) fail("cannot set up the " + info.codec + " decoder: " + av_error_text(code));
  decoder->pkt_timebase = time_base;
  // Two threads: a seek's decode from the key frame is the cost a random read pays.
  decoder->thread_count = 2;
  decoder->thread_type = FF_THREAD_FRAME | FF_THREAD_SLICE;
  code = avcodec_open2(decoder.get(), codec, nullptr);
  if (code < 0) fail("cannot open the " + info.codec + " decoder: " + av_error_text(code));
}

// One pass over the packets, none decoded: their time stamps sorted are the frame times.
void VideoFile::Impl::index_packets() {
  std::vector<int64_t> key_pts;
  int64_t packet_duration = 0;
  while (av_read_frame(format.get(), packet.get()) >= 0) {
    if (packet->stream_index == stream && !(packet->flags & AV_PKT_FLAG_DISCARD)) {
      const int64_t stamp = packet->pts != AV_NOPTS_VALUE ? packet->pts : packet->dts;
      if (stamp != AV_NOPTS_VALUE) {
        pts.push_back(stamp);
        if (packet->flags & AV_PKT_FLAG_KEY) key_pts.push_back(stamp);
        if (packet->duration > 0) packet_duration = packet->duration;
      }
    }
    av_packet_unref(packet.get());
  }
  std::sort(pts.begin(), pts.end());
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  if (pts.empty()) fail("holds no video frames (the file is cut short or damaged)");

  const double unit = av_q2d(time_base);
  times.resize(pts.size());
  for (size_t i = 0; i < pts.size(); ++i) times[i] = static_cast<double>(pts[i] - pts[0]) * unit;

  std::sort(key_pts.begin(), key_pts.end());
  for (int64_t stamp : key_pts) key_frames.push_back(index_of_pts(stamp));
  key_frames.erase(std::unique(key_frames.begin(), key_frames.end()), key_frames.end());
  if (key_frames.empty() || key_frames.front() != 0) key_frames.insert(key_frames.begin(), 0);

  const size_t count = times.size();
  double mean_interval = 0;
  if (count > 1) {
    mean_interval = times.back() / static_cast<double>(count - 1);
  } else if (packet_duration > 0) {
    mean_interval = static_cast<double>(packet_duration) * unit;
  } else {
    const AVRational rate = format->streams[stream]->avg_frame_rate;
    mean_interval = rate.num > 0 && rate.den > 0 ? av_q2d(av_inv_q(rate)) : 1.0 / 25;
  }
  info.frame_count = static_cast<int64_t>(count);
  info.duration = times.back() + mean_interval;
  info.mean_rate = static_cast<double>(count) / info.duration;

  // Variable when an interval differs from the median by more than 1 % (or, for coarse time
  // bases such as Matroska's milliseconds, by more than the rounding to one unit).
  if (count > 2) {
    std::vector<double> intervals(count - 1);
    for (size_t i = 1; i < count; ++i) intervals[i - 1] = times[i] - times[i - 1];
    std::vector<double> sorted = intervals;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double median = sorted[sorted.size() / 2];
    const double allowed = std::max(0.01 * median, 1.5 * unit);
    info.variable_rate = std::any_of(intervals.begin(), intervals.end(), [&](double interval) {
      return std::abs(interval - median) > allowed;
    });
  }
}

int64_t VideoFile::Impl::index_of_pts(int64_t stamp) const {
  const auto found = std::lower_bound(pts.begin(), pts.end(), stamp);
  if (found == pts.end() || *found != stamp) return -1;
  return found - pts.begin();
}

//---- Decoding

// Back to the first packet, the decoder emptied.
void VideoFile::Impl::restart() {
  av_seek_frame(format.get(), stream, pts.front(), AVSEEK_FLAG_BACKWARD);
  avcodec_flush_buffers(decoder.get());
  position = -1;
  draining = false;
  finished = false;
}

void VideoFile::Impl::seek_to_key_frame(size_t key) {
  ++seeks;
  const int64_t target = pts[key_frames[key]];
  int code = av_seek_frame(format.get(), stream, target, AVSEEK_FLAG_BACKWARD);
  if (code < 0)
    code =
        avformat_seek_file(format.get(), stream, INT64_MIN, target, target, AVSEEK_FLAG_BACKWARD);
  if (code < 0) code = av_seek_frame(format.get(), stream, 0, AVSEEK_FLAG_BYTE);
  if (code < 0)
    fail("cannot seek to " + frame_words(key_frames[key], times[key_frames[key]]) + ": " +
         av_error_text(code));
  avcodec_flush_buffers(decoder.get());
  position = -1;
  draining = false;
  finished = false;
}

// The cache's entry for frame `index`: the least recently used one reused when it is full.
VideoFrame& VideoFile::Impl::store(int64_t index) {
  if (static_cast<int>(cache.size()) >= options.cache_frames)
    cache.splice(cache.begin(), cache, std::prev(cache.end()));
  else
    cache.emplace_front();
  VideoFrame& out = cache.front();
  out.index = index;
  out.time = times[index];
  out.duration = (index + 1 < info.frame_count ? times[index + 1] : info.duration) - times[index];
  out.width = output_width;
  out.height = output_height;
  const int channels = options.grey ? 1 : 4;
  out.rgba.resize(static_cast<size_t>(output_width) * output_height * channels);

  const AVFrame* source = decoded.get();
  SwsContext* previous = scale.release();
  scale.reset(sws_getCachedContext(previous, source->width, source->height,
                                   static_cast<AVPixelFormat>(source->format), output_width,
                                   output_height, options.grey ? AV_PIX_FMT_GRAY8 : AV_PIX_FMT_RGBA,
                                   SWS_BILINEAR, nullptr, nullptr, nullptr));
  if (!scale) {
    cache.pop_front();
    const char* name = av_get_pix_fmt_name(static_cast<AVPixelFormat>(source->format));
    fail("cannot convert " + frame_words(index, times[index]) + " from pixel format " +
         in_quotes(name ? name : "unknown"));
  }
  uint8_t* planes[4] = {out.rgba.data(), nullptr, nullptr, nullptr};
  int strides[4] = {output_width * channels, 0, 0, 0};
  sws_scale(scale.get(), source->data, source->linesize, 0, source->height, planes, strides);
  return out;
}

bool VideoFile::Impl::decode_until(int64_t index, VideoFrame*& result) {
  const bool after_seek = position < 0;
  const auto missing = [&](const std::string& why) {
    fail(frame_words(index, times[index]) + " cannot be decoded: " + why);
  };
  while (true) {
    // Every frame the decoder has ready, then one more packet.
    while (true) {
      const int code = avcodec_receive_frame(decoder.get(), decoded.get());
      if (code == AVERROR(EAGAIN)) break;
      if (code == AVERROR_EOF) {
        finished = true;
        missing(position < 0 ? "no frame decodes from the key frame before it (the data there is "
                               "damaged)"
                             : "the data there is damaged or the file is cut short");
      }
      if (code < 0) {
        finished = true;  // the decoder's state is unknown: the next read seeks
        missing("the data there is damaged (" + av_error_text(code) + ")");
      }
      ++decoded_frames;
      int64_t stamp = decoded->best_effort_timestamp;
      if (stamp == AV_NOPTS_VALUE) stamp = decoded->pts;
      const int64_t at = index_of_pts(stamp);
      if (at < 0) continue;  // a frame the index does not hold: nothing can be shown for it
      if (after_seek && position < 0 && at > index) return false;
      if (at <= position) continue;
      position = at;
      if (at == index) {
        result = &store(index);
        return true;
      }
      if (at > index) missing("the data there is damaged (the decoder skipped it)");
    }
    if (draining) continue;  // receive_frame ends with EOF
    const int code = av_read_frame(format.get(), packet.get());
    if (code < 0) {
      // The end, or a read error: what the decoder holds still comes out.
      draining = true;
      avcodec_send_packet(decoder.get(), nullptr);
      continue;
    }
    if (packet->stream_index == stream) {
      // A packet the decoder refuses is damaged; the frames that depend on it are missed and
      // named when they are asked for.
      avcodec_send_packet(decoder.get(), packet.get());
    }
    av_packet_unref(packet.get());
  }
}

const VideoFrame& VideoFile::Impl::frame(int64_t index) {
  if (index < 0 || index >= info.frame_count)
    fail("frame " + std::to_string(index) + " is outside the video's frames 0-" +
         std::to_string(info.frame_count - 1));
  for (auto entry = cache.begin(); entry != cache.end(); ++entry)
    if (entry->index == index) {
      cache.splice(cache.begin(), cache, entry);
      return cache.front();
    }

  // The key frame at or before the wanted one.
  size_t key = static_cast<size_t>(std::upper_bound(key_frames.begin(), key_frames.end(), index) -
                                   key_frames.begin() - 1);
  const bool ahead =
      !finished && index > position &&
      (position >= 0 ? (index - position <= kDecodeForwardWithin || key_frames[key] <= position)
                     : key == 0);
  VideoFrame* result = nullptr;
  if (ahead && decode_until(index, result)) return *result;
  for (int attempt = 0; attempt < kSeekAttempts; ++attempt) {
    seek_to_key_frame(key);
    if (decode_until(index, result)) return *result;
    if (key == 0) break;
    --key;  // the demuxer landed past the wanted frame: start one key frame earlier
  }
  fail(frame_words(index, times[index]) + " cannot be decoded: " +
       (key == 0 ? "the data there is damaged (the decoder skipped it)"
                 : "no seek lands before it (the file's index is damaged)"));
}

//---- The class

VideoFile::VideoFile(const std::string& path, VideoOpenOptions options)
    : impl_(std::make_unique<Impl>()) {
  impl_->path = path;
  impl_->options = options;
  impl_->open();
}

VideoFile::~VideoFile() = default;

const VideoInfo& VideoFile::info() const { return impl_->info; }
const std::vector<double>& VideoFile::frame_times() const { return impl_->times; }

int64_t VideoFile::frame_index_at(double time) const {
  const std::vector<double>& times = impl_->times;
  if (!(time >= 0) || time >= impl_->info.duration) return -1;
  return std::upper_bound(times.begin(), times.end(), time) - times.begin() - 1;
}

const VideoFrame& VideoFile::frame(int64_t index) { return impl_->frame(index); }

int64_t VideoFile::seek_count() const { return impl_->seeks; }
int64_t VideoFile::decoded_frame_count() const { return impl_->decoded_frames; }
size_t VideoFile::cached_bytes() const {
  size_t bytes = 0;
  for (const VideoFrame& cached : impl_->cache) bytes += cached.rgba.capacity();
  return bytes;
}

std::string video_time_problem(const VideoInfo& info, double video_time, double offset) {
  if (video_time < 0) return "before the video (it starts at " + fixed_text(offset, 1) + " s)";
  if (video_time >= info.duration)
    return "past the video's end (it ends at " + fixed_text(offset + info.duration, 1) + " s)";
  return "";
}

}  // namespace tactile
