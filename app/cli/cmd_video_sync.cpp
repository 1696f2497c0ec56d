// `tactile video sync RECORDING NAME (--offset S | --points R1=V1,R2=V2 | --auto [--region
// X,Y,W,H] [--max-lag S] [--accept [--force]])`: sets where an attached video sits on the
// recording's time, by hand or from the proposal of video/video_sync.h (docs/VIDEO.md,
// "Synchronising"). A subcommand of `tactile video` (cmd_video.cpp).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "commands.h"
#include "progress.h"
#include "tactile/error.h"
#include "tactile/signal/sample_source.h"
#include "tactile/video/attachments.h"
#include "tactile/video/video_file.h"
#include "tactile/video/video_sync.h"

namespace tactile::cli {

namespace {

struct VideoSyncOptions {
  std::string recording;
  std::string name;
  std::string offset;  // as given: "" when absent
  std::string points;
  bool automatic = false;
  std::string region;
  std::string max_lag;
  bool accept = false;
  bool force = false;
};

// Proposals are made on a 10 Hz grid and refined between its steps.
constexpr double kSyncRate = 10.0;

double number_of(const std::string& text, const std::string& option, const std::string& form) {
  size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(value))
    throw Error(option, "must be " + form + ", not '" + text + "'");
  return value;
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::stringstream stream(text);
  for (std::string part; std::getline(stream, part, separator);) parts.push_back(part);
  if (!text.empty() && text.back() == separator) parts.emplace_back();
  return parts;
}

VideoRegion parse_region(const std::string& text) {
  const std::string form = "X,Y,W,H: fractions of the picture (0..1), W and H above 0";
  const std::vector<std::string> parts = split(text, ',');
  if (parts.size() != 4) throw Error("--region", "must be " + form + ", not '" + text + "'");
  VideoRegion region{number_of(parts[0], "--region", form), number_of(parts[1], "--region", form),
                     number_of(parts[2], "--region", form), number_of(parts[3], "--region", form)};
  if (region.x < 0 || region.y < 0 || !(region.width > 0) || !(region.height > 0) ||
      region.x + region.width > 1.0 + 1e-9 || region.y + region.height > 1.0 + 1e-9)
    throw Error("--region", "must be " + form + " inside the picture, not '" + text + "'");
  return region;
}

std::string seconds(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3f s", value);
  return text;
}

// The proposal for `attachment` around its present offset; prints it.
SyncProposal propose(const VideoSyncOptions& options, const VideoAttachment& attachment,
                     double max_lag) {
  const std::unique_ptr<SampleSource> source = open_sample_source(options.recording);
  VideoOpenOptions open;
  open.max_width = 160;
  open.grey = true;
  VideoFile video(video_path(options.recording, attachment), open);
  std::optional<VideoRegion> region;
  if (!options.region.empty()) region = parse_region(options.region);

  ProgressBar video_bar("motion energy of " + attachment.name);
  ActivitySeries motion = motion_energy(video, kSyncRate, region, [&](double fraction) {
    video_bar.update(std::llround(fraction * 1000), 1000);
  });
  video_bar.finish();
  ProgressBar skin_bar("activity of the skin");
  const ActivitySeries skin = skin_activity(*source, kSyncRate, [&](double fraction) {
    skin_bar.update(std::llround(fraction * 1000), 1000);
  });
  skin_bar.finish();
  // The motion on recording time: video time v is shown at offset + v / rate, so its grid is
  // `rate` times finer in recording seconds (the offset is what is proposed).
  motion.rate *= attachment.rate;
  motion.start /= attachment.rate;
  const SyncProposal proposal = propose_offset(skin, motion, attachment.offset, max_lag);
  std::printf("proposed offset %s (correlation %.2f, confidence %.2f): %s\n",
              seconds(proposal.offset).c_str(), proposal.correlation, proposal.confidence,
              proposal.sure ? "sure" : ("not sure: " + proposal.why).c_str());
  return proposal;
}

void run_video_sync(const VideoSyncOptions& options) {
  const int ways = (options.offset.empty() ? 0 : 1) + (options.points.empty() ? 0 : 1) +
                   (options.automatic ? 1 : 0);
  if (ways != 1) throw Error("video sync", "give one of --offset, --points and --auto");
  if (!options.automatic) {
    for (const auto& [given, option] : {std::pair{!options.region.empty(), "--region"},
                                        {!options.max_lag.empty(), "--max-lag"},
                                        {options.accept, "--accept"},
                                        {options.force, "--force"}})
      if (given) throw Error(option, "only with --auto");
  }
  if (options.force && !options.accept) throw Error("--force", "only with --accept");

  std::vector<VideoAttachment> attachments = read_attachments(options.recording);
  VideoAttachment* attachment =
      &attachments[attachment_index(attachments, options.name, options.recording)];

  if (!options.offset.empty()) {
    attachment->offset = number_of(options.offset, "--offset", "a number of seconds");
  } else if (!options.points.empty()) {
    const std::string form = "R1=V1,R2=V2: recording and video seconds of two instants";
    const std::vector<std::string> pairs = split(options.points, ',');
    if (pairs.size() != 2)
      throw Error("--points", "must be " + form + ", not '" + options.points + "'");
    double values[4];
    for (size_t k = 0; k < 2; ++k) {
      const std::vector<std::string> sides = split(pairs[k], '=');
      if (sides.size() != 2)
        throw Error("--points", "must be " + form + ", not '" + options.points + "'");
      values[2 * k] = number_of(sides[0], "--points", form);
      values[2 * k + 1] = number_of(sides[1], "--points", form);
    }
    try {
      sync_from_two_points(*attachment, values[0], values[1], values[2], values[3]);
    } catch (const Error& error) {
      throw Error("--points", error.message());
    }
  } else {
    const double max_lag = options.max_lag.empty()
                               ? 30.0
                               : number_of(options.max_lag, "--max-lag", "a number of seconds");
    if (!(max_lag > 0)) throw Error("--max-lag", "must be above 0 s");
    const SyncProposal proposal = propose(options, *attachment, max_lag);
    if (!options.accept) {
      std::printf("not written (--accept writes it)\n");
      return;
    }
    if (!proposal.sure && !options.force)
      throw Error("--accept",
                  "the proposal is not sure (" + proposal.why + "); --force writes it anyway");
    attachment->offset = proposal.offset;
  }
  write_attachments(options.recording, attachments);
  std::printf("%s: video %s at offset %s, rate %.6g\n", options.recording.c_str(),
              attachment->name.c_str(), seconds(attachment->offset).c_str(), attachment->rate);
}

}  // namespace

void register_video_sync(CLI::App& video) {
  auto options = std::make_shared<VideoSyncOptions>();
  CLI::App* command = video.add_subcommand(
      "sync", "Set where an attached video sits on the recording's time, or propose it");
  command->add_option("recording", options->recording, "Recording")->required();
  command->add_option("name", options->name, "The attached video's name")->required();
  command->add_option("--offset", options->offset,
                      "Recording time (s) at which the video's time 0 is shown");
  command->add_option("--points", options->points,
                      "R1=V1,R2=V2: two instants seen in both (recording and video seconds); "
                      "sets offset and rate");
  command->add_flag("--auto", options->automatic,
                    "Propose the offset from the video's motion and the skin's activity");
  command->add_option("--region", options->region,
                      "X,Y,W,H: only this part of the picture moves with the touches (fractions)");
  command->add_option("--max-lag", options->max_lag,
                      "Search this many seconds either side of the present offset (default 30)");
  command->add_flag("--accept", options->accept, "Write the proposal (when it is sure)");
  command->add_flag("--force", options->force, "With --accept: write it even when not sure");
  command->callback([options] { run_video_sync(*options); });
}

}  // namespace tactile::cli
