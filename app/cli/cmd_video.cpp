// `tactile video attach|list|detach`: videos beside a recording (docs/VIDEO.md). Each video is
// opened (indexed, its first frame decoded) before it is attached, so a file that cannot be
// shown is refused here and not later in the workbench.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "commands.h"
#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/text.h"
#include "tactile/video/attachments.h"
#include "tactile/video/video_file.h"

namespace tactile::cli {

namespace {

struct VideoOptions {
  std::string recording;
  std::string video;
  std::string name;
  double offset = 0;
  double rate = 1;
  bool json = false;
};

// The recording's end: its longest stream's (as `tactile info` gives the streams).
double recording_length(const std::string& recording) {
  const RecordingFile file(recording);
  double length = 0;
  for (const StreamInfo& stream : file.streams()) length = std::max(length, stream.duration());
  return length;
}

void require_recording(const std::string& recording) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(recording, error))
    throw Error(recording, "no such recording");
}

std::string rate_words(const VideoInfo& info) {
  return info.variable_rate ? "variable rate (mean " + fixed_text(info.mean_rate, 2) + " fps)"
                            : fixed_text(info.mean_rate, 2) + " fps";
}

//---- attach

void run_attach(const VideoOptions& options) {
  require_recording(options.recording);
  if (!std::isfinite(options.offset))
    throw Error("--offset",
                "must be a finite number of seconds, not " + shortest_text(options.offset));
  if (!(options.rate > 0) || !std::isfinite(options.rate))
    throw Error("--rate", "must be a positive number (video seconds per recording second), not " +
                              shortest_text(options.rate));
  if (!options.name.empty() && !valid_attachment_name(options.name))
    throw Error("--name",
                "may hold only letters, digits, '-', '_' and '.', not " + in_quotes(options.name));
  std::vector<VideoAttachment> attachments = read_attachments(options.recording);
  const double length = recording_length(options.recording);
  const VideoFile video(options.video);
  const VideoInfo& info = video.info();

  VideoAttachment attachment;
  attachment.name =
      options.name.empty() ? free_attachment_name(attachments, options.video) : options.name;
  if (find_attachment(attachments, attachment.name))
    throw Error("--name", "a video named " + in_quotes(attachment.name) +
                              " is already attached to " + options.recording +
                              "; choose another --name or detach it first");
  attachment.path = kept_video_path(options.recording, options.video);
  attachment.offset = options.offset;
  attachment.rate = options.rate;
  attachments.push_back(attachment);
  write_attachments(options.recording, attachments);

  std::cout << "attached " << in_quotes(attachment.name) << ": " << attachment.path << ", "
            << info.codec << " " << info.width << "x" << info.height << ", "
            << fixed_text(info.duration, 2) << " s, " << info.frame_count << " frames, "
            << rate_words(info) << ", offset " << seconds_text(attachment.offset) << " s"
            << (attachment.rate != 1 ? ", rate " + shortest_text(attachment.rate) : "") << "\n";
  const double start = attachment.recording_time(0);
  const double end = attachment.recording_time(info.duration);
  // Said when the video leaves part of the recording without a picture, or begins before it.
  if (start != 0 || end < length)
    std::cerr << "tactile: warning: the video covers " << fixed_text(start, 1) << "-"
              << fixed_text(end, 1) << " s of the recording's 0-" << fixed_text(length, 1)
              << " s\n";
}

//---- list

void run_list(const VideoOptions& options) {
  require_recording(options.recording);
  const std::vector<VideoAttachment> attachments = read_attachments(options.recording);
  nlohmann::json videos = nlohmann::json::array();
  std::ostringstream out;
  if (attachments.empty() && !options.json)
    out << "no videos attached to " << options.recording << "\n";
  for (const VideoAttachment& attachment : attachments) {
    const std::string file = video_path(options.recording, attachment);
    std::string problem;
    std::string summary;
    std::error_code error;
    if (!std::filesystem::exists(file, error)) {
      problem = "missing";
    } else {
      try {
        const VideoFile video(file);
        summary = video.info().codec + ", " + fixed_text(video.info().duration, 2) + " s";
      } catch (const Error& failure) {
        problem = failure.message();
      }
    }
    videos.push_back(
        {{"name", attachment.name},
         {"path", attachment.path},
         {"file", file},
         {"offset", attachment.offset},
         {"rate", attachment.rate},
         {"problem", problem.empty() ? nlohmann::json(nullptr) : nlohmann::json(problem)}});
    out << attachment.name << "  " << attachment.path << "  offset "
        << seconds_text(attachment.offset) << " s  rate " << shortest_text(attachment.rate) << "  "
        << (problem.empty() ? summary : problem) << "\n";
  }
  if (options.json)
    std::cout << nlohmann::json{{"recording", options.recording}, {"videos", videos}}.dump(2)
              << "\n";
  else
    std::cout << out.str();
}

//---- detach

void run_detach(const VideoOptions& options) {
  require_recording(options.recording);
  std::vector<VideoAttachment> attachments = read_attachments(options.recording);
  const auto found = attachments.begin() + static_cast<std::ptrdiff_t>(attachment_index(
                                               attachments, options.name, options.recording));
  const std::string path = found->path;
  attachments.erase(found);
  write_attachments(options.recording, attachments);
  std::cout << "detached " << in_quotes(options.name) << " (" << path
            << "; the video file is left where it is)\n";
}

}  // namespace

void register_video(CLI::App& app) {
  CLI::App* video = app.add_subcommand("video", "Videos beside a recording: attach, list, detach");
  video->require_subcommand(1);

  auto attach = std::make_shared<VideoOptions>();
  CLI::App* command =
      video->add_subcommand("attach",
                            "Attach a video to a recording (checked by opening it; kept in "
                            "RECORDING.videos.json)");
  command->add_option("RECORDING", attach->recording, "Recording file (.h5)")->required();
  command->add_option("VIDEO", attach->video, "Video file (.mp4, .mkv, .avi, .mov, .webm, ...)")
      ->required();
  command->add_option("--name", attach->name,
                      "Name of the attachment: letters, digits, '-', '_', '.' (default: the "
                      "video's file name without extension, numbered when taken)");
  command->add_option("--offset", attach->offset,
                      "Recording time (s) at which the video's first frame is shown; may be "
                      "negative (default 0)");
  command->add_option("--rate", attach->rate,
                      "Video seconds per recording second, for clocks that drift (default 1)");
  command->callback([attach] { run_attach(*attach); });

  auto list = std::make_shared<VideoOptions>();
  command = video->add_subcommand("list", "List a recording's videos and whether each opens");
  command->add_option("RECORDING", list->recording, "Recording file (.h5)")->required();
  command->add_flag("--json", list->json, "Print JSON instead of text");
  command->callback([list] { run_list(*list); });

  auto detach = std::make_shared<VideoOptions>();
  command = video->add_subcommand("detach", "Detach a video (the video file itself is left)");
  command->add_option("RECORDING", detach->recording, "Recording file (.h5)")->required();
  command->add_option("NAME", detach->name, "Name of the attachment (see `tactile video list`)")
      ->required();
  command->callback([detach] { run_detach(*detach); });

  register_video_sync(*video);
}

}  // namespace tactile::cli
