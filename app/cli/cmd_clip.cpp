// `tactile clip RECORDING --label ID [--video NAME] --out CLIP.mp4`: a clip of one label as a
// talk shows it. The drawing is the workbench's own (its "clip" view, rendered off-screen with
// OSMesa), so this command runs tactile-workbench-headless, installed beside `tactile`, and
// keeps the command line itself free of ImGui.
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "tactile/cluster/slurm.h"
#include "tactile/error.h"
#include "tactile/text.h"

namespace tactile::cli {

namespace {

namespace fs = std::filesystem;

struct ClipArgs {
  std::string recording, out, video, labels;
  int64_t label = -1;
  double margin = 1.0;
  double rate = 30.0;
  int width = 1280, height = 720;
};

void run_clip(const ClipArgs& args) {
  const std::string extension = fs::path(args.out).extension().string();
  if (extension != ".mp4" && extension != ".mkv" && extension != ".mov" && extension != ".avi" &&
      extension != ".webm")
    throw Error("--out", in_quotes(args.out) + ": a clip is .mp4, .mkv, .mov, .avi or .webm");
  std::vector<std::string> words = {cluster::program_beside_this_one("tactile-workbench-headless"),
                                    args.recording,
                                    "--clip-label",
                                    std::to_string(args.label),
                                    "--clip-out",
                                    args.out,
                                    "--clip-margin",
                                    shortest_text(args.margin),
                                    "--clip-rate",
                                    shortest_text(args.rate),
                                    "--width",
                                    std::to_string(args.width),
                                    "--height",
                                    std::to_string(args.height)};
  if (!args.video.empty()) words.insert(words.end(), {"--clip-video", args.video});
  if (!args.labels.empty()) words.insert(words.end(), {"--labels", args.labels});
  const cluster::ProgramOutput drawn = cluster::run_captured(words);
  if (drawn.exit_code != 0) {
    std::string said = drawn.out;
    while (!said.empty() && said.back() == '\n') said.pop_back();
    // The renderer's own line ("tactile-workbench: clip: ... has no label 99") says what.
    const size_t last = said.rfind('\n');
    throw Error("tactile clip",
                "no clip written: " + (said.empty() ? "the renderer failed (exit " +
                                                          std::to_string(drawn.exit_code) + ")"
                                                    : said.substr(last + 1)));
  }
  std::cout << drawn.out;
}

}  // namespace

void register_clip(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "clip",
      "Encode a clip of one label: the skin and the video replaying side by side, the signals "
      "with the cursor and the label's lanes (docs/VIDEO.md)");
  auto args = std::make_shared<ClipArgs>();
  command->add_option("recording", args->recording, "The recording (.h5)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--label", args->label, "The label's id (tactile labels list)")
      ->required()
      ->check(CLI::NonNegativeNumber);
  command->add_option("--out", args->out, "The clip: .mp4 (H.264), .mkv, .mov, .avi, .webm")
      ->required();
  command->add_option("--video", args->video,
                      "The attached video shown (tactile video list); default every one");
  command->add_option("--labels", args->labels,
                      "Label database (default: labels.db beside the recording)");
  command->add_option("--margin", args->margin, "Seconds before and after the label (default 1)")
      ->check(CLI::Range(0.0, 600.0));
  command->add_option("--rate", args->rate, "Frames per second (default 30)")
      ->check(CLI::Range(1.0, 120.0));
  command->add_option("--width", args->width, "Width in pixels (default 1280)")
      ->check(CLI::Range(320, 3840));
  command->add_option("--height", args->height, "Height in pixels (default 720)")
      ->check(CLI::Range(240, 2160));
  command->callback([args] { run_clip(*args); });
}

}  // namespace tactile::cli
