// Videos beside the skin, driven through ImGui's input path (docs/VIDEO.md): a video attached
// from the Video menu, nudged by a key and undone, a confusion cell clicked through to the touch
// with its video at that instant; the frame shown read back from the window's pixels (each test
// video codes its frame number in its picture, tests/support/video_test_files.h); a clip of a
// label decoded and looked at.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "cli_test_support.h"
#include "png_test_support.h"
#include "tactile/video/attachments.h"
#include "tactile/video/video_file.h"
#include "temp_folder.h"
#include "video_test_files.h"

namespace tactile {
namespace {

namespace fs = std::filesystem;

constexpr double kVideoRate = 10.0;  // frames per second of the test videos

class WorkbenchVideo : public ::testing::Test {
 protected:
  WorkbenchVideo() : folder("tactile-workbench-video") {}

  void SetUp() override {
    const auto made = test::run_program(
        "tactile", "simulate --skin flux --subjects 2 --repetitions 3 --out " + flux(), folder);
    ASSERT_EQ(made.exit_code, 0) << made.err;
    for (const auto& entry : fs::directory_iterator(flux()))
      if (entry.path().extension() == ".h5") recordings.push_back(entry.path().string());
    std::sort(recordings.begin(), recordings.end());
    ASSERT_GE(recordings.size(), 2u);
  }

  std::string flux() const { return folder.file("flux"); }

  // A numbered video of `seconds` at kVideoRate beside the recordings.
  std::string make_video(const std::string& name, double seconds) const {
    const std::string path = folder.file("flux/" + name);
    test::write_numbered_video(
        path,
        test::constant_rate_times(static_cast<int>(std::ceil(seconds * kVideoRate)), kVideoRate),
        160, 120, "", kVideoRate);
    return path;
  }

  // The recording's duration, as `tactile info --json` gives it.
  double duration(const std::string& recording) const {
    const auto info = test::run_program("tactile", "info --json " + recording, folder);
    EXPECT_EQ(info.exit_code, 0) << info.err;
    return nlohmann::json::parse(info.out)["streams"][0]["duration_s"].get<double>();
  }

  test::CommandResult workbench(const std::string& arguments, const std::string& text) const {
    return test::run_program("tactile-workbench-headless",
                             arguments + " --annotator ana --size 1400x800 --settings " +
                                 folder.file("settings.json") + " --script " +
                                 test::write_script(folder, text),
                             folder);
  }

  nlohmann::json state(const std::string& name) const {
    std::ifstream in(folder.file(name));
    return nlohmann::json::parse(in);
  }

  // The number the video `name` shows in a screenshot, read inside its picture's box.
  int number_on_screen(const std::string& png_name, const nlohmann::json& shot_state,
                       const std::string& name) const {
    const Png png = read_png(folder.file(png_name));
    EXPECT_TRUE(png.pixels) << png_name;
    const nlohmann::json& box = shot_state["boxes"]["video:picture:" + name];
    EXPECT_FALSE(box.is_null()) << name << " has no picture in " << png_name;
    if (!png.pixels || box.is_null()) return -1;
    return number_in_box(box, [&](int x, int y) { return png.at(x, y); });
  }

  // The number shown inside a state's `box` of an image whose pixel (x, y) is `pixel(x, y)`
  // (RGBA); the box's edge pixels, half covered, are left out.
  static int number_in_box(const nlohmann::json& box,
                           const std::function<const uint8_t*(int, int)>& pixel) {
    const int x0 = static_cast<int>(std::ceil(box["x"].get<double>()));
    const int y0 = static_cast<int>(std::ceil(box["y"].get<double>()));
    const int width = static_cast<int>(box["width"].get<double>()) - 1;
    const int height = static_cast<int>(box["height"].get<double>()) - 1;
    std::vector<uint8_t> picture(static_cast<size_t>(width) * height * 4);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        std::copy_n(pixel(x0 + x, y0 + y), 4, &picture[(static_cast<size_t>(y) * width + x) * 4]);
    return test::number_in_image(picture.data(), width, height, 4);
  }

  // The frame a video at `offset` shows at recording time `time`.
  static int64_t frame_at(double time, double offset) {
    return static_cast<int64_t>(std::floor((time - offset) * kVideoRate + 1e-6));
  }

  static const nlohmann::json* video_named(const nlohmann::json& shot_state,
                                           const std::string& name) {
    for (const nlohmann::json& video : shot_state["videos"]["list"])
      if (video["name"] == name) return &video;
    return nullptr;
  }

  test::TempFolder folder;
  std::vector<std::string> recordings;
};

TEST_F(WorkbenchVideo, AttachNudgeUndoAndAConfusionClickShowTheVideoAtTheTouch) {
  // Every recording has its front camera, attached on the command line; the first gets a second
  // camera from the Video menu.
  for (const std::string& recording : recordings) {
    const std::string video =
        make_video(fs::path(recording).stem().string() + "-front.mp4", duration(recording) + 1.0);
    const auto attached = test::run_program(
        "tactile", "video attach " + recording + " " + video + " --name front", folder);
    ASSERT_EQ(attached.exit_code, 0) << attached.err;
  }
  const std::string side = make_video("side.mkv", duration(recordings[0]) + 1.0);
  // An evaluation of the recordings, so that a confusion cell leads to a touch.
  const std::string table = folder.file("features.csv");
  ASSERT_EQ(test::run_program(
                "tactile",
                "features --pipeline flux --labels " + flux() + "/labels.db --out " + table, folder)
                .exit_code,
            0);
  ASSERT_EQ(test::run_program("tactile",
                              "evaluate --features " + table +
                                  " --classifier knn --protocol kfold:3 --out " +
                                  folder.file("result.json"),
                              folder)
                .exit_code,
            0);
  std::ifstream in(folder.file("result.json"));
  const nlohmann::json result = nlohmann::json::parse(in);
  const auto classes = result["classes"].get<std::vector<std::string>>();
  const auto confusion = result["confusion"].get<std::vector<std::vector<int>>>();
  std::string truth = classes[0], predicted = classes[0];
  for (size_t row = 0; row < classes.size(); ++row)
    for (size_t column = 0; column < classes.size(); ++column)
      if (row != column && confusion[row][column] > 0)
        truth = classes[row], predicted = classes[column];

  const auto run = workbench(
      recordings[0] + " --evaluation " + folder.file("result.json"),
      "wait 2\nmenu Video/Attach video...\nwait 1\nclick item browser:path\ntype " + side +
          "\nclick item browser:OK\nwait jobs\nwait video\nstate @attached.json\n"
          "screenshot @attached.png\n"
          "key Alt+Right\nwait video\nstate @nudged.json\nscreenshot @nudged.png\n"
          "key Ctrl+Z\nwait video\nstate @undone.json\n"
          "click item tab:confusion\nwait 2\nclick cell " +
          truth + " " + predicted +
          "\nwait 2\nkey Enter\nwait 8\nwait video\nstate @landed.json\n"
          "screenshot @landed.png\n");
  ASSERT_EQ(run.exit_code, 0) << run.err;

  // Attached: two videos side by side, each at the frame of the cursor, on the screen too.
  const nlohmann::json attached = state("attached.json");
  ASSERT_EQ(attached["videos"]["list"].size(), 2u) << attached["videos"] << attached["error"];
  const double time = attached["time"];
  for (const char* name : {"front", "side"}) {
    const nlohmann::json* video = video_named(attached, name);
    ASSERT_NE(video, nullptr) << name;
    EXPECT_EQ((*video)["frame"], frame_at(time, 0.0)) << name;
    EXPECT_EQ(number_on_screen("attached.png", attached, name), frame_at(time, 0.0)) << name;
  }
  // The menu's video is selected: Alt+Right shows it one frame later, the other stays.
  const nlohmann::json nudged = state("nudged.json");
  EXPECT_NEAR((*video_named(nudged, "side"))["offset"].get<double>(), 1.0 / kVideoRate, 1e-9);
  EXPECT_EQ((*video_named(nudged, "front"))["offset"], 0.0);
  EXPECT_EQ(number_on_screen("nudged.png", nudged, "side"), frame_at(time, 1.0 / kVideoRate));
  EXPECT_EQ(number_on_screen("nudged.png", nudged, "front"), frame_at(time, 0.0));
  // Kept at once beside the recording; Ctrl+Z takes the nudge back, in the file too.
  const nlohmann::json undone = state("undone.json");
  EXPECT_EQ((*video_named(undone, "side"))["offset"], 0.0);
  std::ifstream kept(recordings[0] + ".videos.json");
  ASSERT_TRUE(kept) << "no " << recordings[0] << ".videos.json";
  const nlohmann::json kept_videos = nlohmann::json::parse(kept);
  for (const nlohmann::json& entry : kept_videos["videos"])
    EXPECT_EQ(entry["offset"], 0.0) << entry;

  // The click on a cell lands on the touch, whose recording's front video shows that instant.
  const nlohmann::json landed = state("landed.json");
  ASSERT_FALSE(landed["analysis"]["landed"].is_null()) << landed["error"];
  EXPECT_EQ(landed["recording"], landed["analysis"]["landed"]["recording"]);
  const double landed_time = landed["time"];
  EXPECT_GE(landed_time, landed["analysis"]["landed"]["t0"].get<double>() - 1e-6);
  const nlohmann::json* front = video_named(landed, "front");
  ASSERT_NE(front, nullptr) << landed["videos"];
  EXPECT_EQ((*front)["frame"], frame_at(landed_time, 0.0));
  EXPECT_EQ(number_on_screen("landed.png", landed, "front"), frame_at(landed_time, 0.0));
}

TEST_F(WorkbenchVideo, StepsFramesAndSaysWhereTheVideoDoesNotReach) {
  const std::string recording = recordings[0];
  // A short video that starts 2 s into the recording.
  const std::string video = make_video("short.mp4", 3.0);
  ASSERT_EQ(test::run_program("tactile", "video attach " + recording + " " + video + " --offset 2",
                              folder)
                .exit_code,
            0);
  const auto run =
      workbench(recording,
                "wait 2\ntime 3.05\nwait video\nstate @at.json\nkey .\nkey .\n"
                "wait video\nstate @stepped.json\nkey ,\nwait video\nstate @back.json\n"
                "time 1\nwait video\nstate @before.json\ntime 6\nwait video\n"
                "state @after.json\n");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(state("at.json")["videos"]["list"][0]["frame"], 10);
  const nlohmann::json stepped = state("stepped.json");
  EXPECT_EQ(stepped["videos"]["list"][0]["frame"], 12);
  EXPECT_NEAR(stepped["time"].get<double>(), 2.0 + 12 / kVideoRate, 1e-3);
  EXPECT_EQ(state("back.json")["videos"]["list"][0]["frame"], 11);
  for (const char* name : {"before.json", "after.json"}) {
    const nlohmann::json outside = state(name)["videos"]["list"][0];
    EXPECT_TRUE(outside["frame"].is_null()) << name;
    EXPECT_NE(outside["problem"].get<std::string>().find(
                  std::string(name) == "before.json" ? "before the video" : "past the video's end"),
              std::string::npos)
        << outside["problem"];
  }
}

TEST_F(WorkbenchVideo, ADragNudgesAsOneEditThatCtrlZTakesBackAndARegionFeedsTheProposal) {
  const std::string recording = recordings[0];
  const std::string video = make_video("short.mp4", duration(recording));
  ASSERT_EQ(test::run_program("tactile", "video attach " + recording + " " + video + " --offset 2",
                              folder)
                .exit_code,
            0);
  const auto run = workbench(
      recording,
      "wait 2\ntime 5\nwait video\ndrag item video:short 0.4 0.5 0.6 0.5\nwait video\n"
      "state @dragged.json\nkey Ctrl+Z\nwait video\nstate @undone.json\n"
      "click item button:video:region\nwait 1\ndrag item video:short 0.3 0.2 0.7 0.8\nwait 1\n"
      "click item button:video:propose\nwait jobs\nstate @proposed.json\n");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // Dragged right: shown later against the skin, by 10 ms a pixel; one edit.
  const nlohmann::json dragged = state("dragged.json")["videos"];
  EXPECT_GT(dragged["list"][0]["offset"].get<double>(), 2.5);
  EXPECT_EQ(dragged["undo"], 1);
  // Ctrl+Z: back to 2 exactly, in the window and in the file, and nothing left to undo.
  const nlohmann::json undone = state("undone.json")["videos"];
  EXPECT_EQ(undone["list"][0]["offset"], 2.0);
  EXPECT_EQ(undone["undo"], 0);
  EXPECT_EQ(read_attachments(recording).front().offset, 2.0);
  // The region drawn is kept for the proposal, which the job makes.
  const nlohmann::json proposed = state("proposed.json");
  const nlohmann::json& region = proposed["videos"]["region"];
  ASSERT_FALSE(region.is_null()) << proposed["videos"];
  EXPECT_GT(region["width"].get<double>(), 0.1);
  EXPECT_LE(region["x"].get<double>() + region["width"].get<double>(), 1.0);
  ASSERT_FALSE(proposed["videos"]["proposal"].is_null()) << proposed["error"];
  EXPECT_EQ(proposed["videos"]["proposal"]["video"], "short");
}

TEST_F(WorkbenchVideo, ALiveReplayPlaysTheRecordingsVideoWithIt) {
  const std::string recording = recordings[0];
  const std::string video = make_video("replayed.mp4", duration(recording));
  ASSERT_EQ(
      test::run_program("tactile", "video attach " + recording + " " + video, folder).exit_code, 0);
  const auto run =
      test::run_program("tactile-workbench-headless",
                        "--connect replay://" + recording + " --size 1400x800 --settings " +
                            folder.file("settings.json") + " --script " +
                            test::write_script(folder, "sleep 2\nwait video\nstate @replay.json\n"),
                        folder);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json replay = state("replay.json");
  ASSERT_EQ(replay["videos"]["list"].size(), 1u) << replay["videos"];
  const double time = replay["time"];
  EXPECT_GT(time, 1.0);
  EXPECT_EQ(replay["videos"]["list"][0]["frame"], frame_at(time, 0.0));
}

TEST_F(WorkbenchVideo, AMissingOrCorruptVideoIsNamedAndTheRecordingStillWorks) {
  const std::string recording = recordings[0];
  const std::string video = make_video("gone.mp4", 2.0);
  ASSERT_EQ(
      test::run_program("tactile", "video attach " + recording + " " + video, folder).exit_code, 0);
  fs::remove(video);
  std::ofstream(folder.file("flux/noise.mp4")) << "this is not a video";
  const std::string labels_before = [&] {
    const auto listed =
        test::run_program("tactile", "labels list " + flux() + "/labels.db", folder);
    return listed.out;
  }();
  const auto run = workbench(recording,
                             "wait 2\nwait video\nstate @missing.json\nmenu Video/Attach video...\n"
                             "wait 1\nclick item browser:path\ntype " +
                                 folder.file("flux/noise.mp4") +
                                 "\nclick item browser:OK\nwait jobs\nstate @refused.json\n"
                                 "key Space\nwait 10\nkey Space\nstate @played.json\n");
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json missing = state("missing.json");
  ASSERT_EQ(missing["videos"]["list"].size(), 1u);
  EXPECT_NE(missing["videos"]["list"][0]["problem"].get<std::string>().find("gone.mp4"),
            std::string::npos)
      << missing["videos"]["list"][0]["problem"];
  const nlohmann::json refused = state("refused.json");
  EXPECT_NE(refused["error"].get<std::string>().find("noise.mp4"), std::string::npos)
      << refused["error"];
  EXPECT_EQ(refused["videos"]["list"].size(), 1u);
  EXPECT_GT(state("played.json")["time"].get<double>(), missing["time"].get<double>());
  EXPECT_GT(state("played.json")["labels"].get<int>(), 0);
  EXPECT_EQ(test::run_program("tactile", "labels list " + flux() + "/labels.db", folder).out,
            labels_before);
}

TEST_F(WorkbenchVideo, AClipShowsTheVideoTheSkinAndTheLanes) {
  const std::string recording = recordings[0];
  const std::string video = make_video("front.mp4", duration(recording) + 1.0);
  ASSERT_EQ(test::run_program("tactile",
                              "video attach " + recording + " " + video + " --name front", folder)
                .exit_code,
            0);
  // The first label of the recording.
  const auto listed = test::run_program(
      "tactile", "labels export " + flux() + "/labels.db --json " + folder.file("labels.json"),
      folder);
  ASSERT_EQ(listed.exit_code, 0) << listed.err;
  std::ifstream in(folder.file("labels.json"));
  const nlohmann::json labels = nlohmann::json::parse(in);
  const std::string id = fs::path(recording).stem().string();
  nlohmann::json label;
  for (const nlohmann::json& candidate : labels["labels"])
    if (candidate["recording"] == id) {
      label = candidate;
      break;
    }
  ASSERT_FALSE(label.is_null()) << labels.dump().substr(0, 400);
  const std::string clip = folder.file("clip.mp4");
  const auto made = test::run_program("tactile",
                                      "clip " + recording + " --label " +
                                          std::to_string(label["id"].get<int64_t>()) + " --out " +
                                          clip + " --rate 10 --margin 0.5 --width 960 --height 540",
                                      folder);
  ASSERT_EQ(made.exit_code, 0) << made.err << made.out;

  // Where the clip view draws the video: the same view at the same size, asked for its boxes.
  const double t0 = label["t0"], t1 = label["t1"];
  const double start = std::max(0.0, t0 - 0.5);
  const auto layout = test::run_program(
      "tactile-workbench-headless",
      recording + " --view clip --size 960x540 --settings " + folder.file("settings.json") +
          " --script " +
          test::write_script(folder, "wait 2\ntime " + std::to_string(start) +
                                         "\nwait video\nstate @clip-layout.json\n"),
      folder);
  ASSERT_EQ(layout.exit_code, 0) << layout.err;
  const nlohmann::json box = state("clip-layout.json")["boxes"]["video:picture:front"];
  ASSERT_FALSE(box.is_null());

  // The same from the window: View > Export clip of the label clicked in its lane.
  const double middle = 0.5 * (label["t0"].get<double>() + label["t1"].get<double>());
  const auto exported =
      workbench(recording, "wait 2\nclick time " + std::to_string(middle) +
                               " in lane:ground-truth\nwait 1\nmenu View/Export clip...\nwait 1\n"
                               "state @asked.json\nclick item browser:OK\nwait jobs\n"
                               "state @exported.json\n");
  ASSERT_EQ(exported.exit_code, 0) << exported.err;
  const nlohmann::json asked = state("asked.json");
  ASSERT_EQ(asked["selection"]["labels"].size(), 1u) << asked["error"];
  const std::string notice = state("exported.json")["notice"];
  ASSERT_EQ(notice.rfind("wrote clip ", 0), 0u) << notice << state("exported.json")["error"];
  EXPECT_GT(VideoFile(notice.substr(11)).info().frame_count, 10);

  VideoFile decoded(clip);
  const int64_t expected_frames =
      static_cast<int64_t>(std::floor((std::min(t1 + 0.5, duration(recording)) - start) * 10)) + 1;
  EXPECT_NEAR(decoded.info().frame_count, expected_frames, 1);
  EXPECT_EQ(decoded.info().width, 960);
  for (int64_t k : {int64_t{0}, decoded.info().frame_count / 2}) {
    const VideoFrame& frame = decoded.frame(k);
    const double at = start + static_cast<double>(k) / 10.0;
    // The video's picture, read in the clip's frame.
    EXPECT_EQ(number_in_box(box,
                            [&](int x, int y) {
                              return &frame.rgba[(static_cast<size_t>(y) * frame.width + x) * 4];
                            }),
              frame_at(at, 0.0))
        << "clip frame " << k;
    // The skin (left of the video) and the lanes (the bottom band) are drawn, not empty.
    std::set<uint32_t> skin_colours, lane_colours;
    for (int y = 40; y < 280; y += 3)
      for (int x = 20; x < 440; x += 3) {
        const uint8_t* p = &frame.rgba[(static_cast<size_t>(y) * frame.width + x) * 4];
        skin_colours.insert((p[0] >> 3) << 10 | (p[1] >> 3) << 5 | (p[2] >> 3));
      }
    for (int y = 450; y < 530; y += 2)
      for (int x = 0; x < 960; x += 3) {
        const uint8_t* p = &frame.rgba[(static_cast<size_t>(y) * frame.width + x) * 4];
        lane_colours.insert((p[0] >> 3) << 10 | (p[1] >> 3) << 5 | (p[2] >> 3));
      }
    EXPECT_GT(skin_colours.size(), 10u) << "clip frame " << k << ": no skin drawn";
    EXPECT_GT(lane_colours.size(), 4u) << "clip frame " << k << ": no lanes drawn";
  }
}

}  // namespace
}  // namespace tactile
