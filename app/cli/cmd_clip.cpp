// `tactile clip RECORDING --label ID [--video NAME] --out CLIP.mp4`: a clip of one label as a
// talk shows it. The drawing is the workbench's own (its "clip" view, rendered off-screen with
// OSMesa), so this command runs tactile-workbench-headless, installed beside `tactile`, and
// keeps the command line itself free of ImGui.
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
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

std::string renderer_path() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  const fs::path beside = self.parent_path() / "tactile-workbench-headless";
  if (error || !fs::exists(beside))
    throw Error("tactile clip",
                "the clip is drawn by tactile-workbench-headless, which is not "
                "beside this program (" +
                    beside.string() + ")");
  return beside.string();
}

void run_clip(const ClipArgs& args) {
  const std::string extension = fs::path(args.out).extension().string();
  if (extension != ".mp4" && extension != ".mkv" && extension != ".mov" && extension != ".avi" &&
      extension != ".webm")
    throw Error("--out", in_quotes(args.out) + ": a clip is .mp4, .mkv, .mov, .avi or .webm");
  std::vector<std::string> words = {renderer_path(), args.recording,
                                    "--clip-label",  std::to_string(args.label),
                                    "--clip-out",    args.out,
                                    "--clip-margin", shortest_text(args.margin),
                                    "--clip-rate",   shortest_text(args.rate),
                                    "--width",       std::to_string(args.width),
                                    "--height",      std::to_string(args.height)};
  if (!args.video.empty()) words.insert(words.end(), {"--clip-video", args.video});
  if (!args.labels.empty()) words.insert(words.end(), {"--labels", args.labels});
  std::vector<char*> argv;
  for (std::string& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);
  const pid_t child = fork();
  if (child < 0) throw Error("tactile clip", system_error("cannot start the renderer"));
  if (child == 0) {
    execv(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  while (waitpid(child, &status, 0) < 0)
    if (errno != EINTR) throw Error("tactile clip", system_error("waiting for the renderer"));
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw Error(
        "tactile clip",
        "no clip written: the renderer (" + words[0] + ") " +
            (WIFEXITED(status) ? "ended with exit code " + std::to_string(WEXITSTATUS(status))
                               : "was killed by signal " + std::to_string(WTERMSIG(status))));
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
