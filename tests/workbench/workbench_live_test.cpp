// Live mode end to end: `tactile stream-sim` sends a simulated fur skin over UDP into a
// headless workbench driven by a script, which shows the skin live (pixels checked),
// records a file (read back), classifies online with a saved model (decisions in `state`),
// and labels while recording (into the recording's label database). Every wait is bounded.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "cli_test_support.h"
#include "png_test_support.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/live/packets.h"
#include "tactile/sim/simulator.h"
#include "tactile/skins/skin.h"
#include "tactile/video/attachments.h"
#include "tactile/video/video_file.h"

namespace tactile {
namespace {

using test::CommandResult;
using test::run_program;

class WorkbenchLive : public ::testing::Test {
 protected:
  std::string script(const std::string& text) { return test::write_script(folder, text); }
  nlohmann::json state(const std::string& name) {
    std::ifstream in(folder.file(name));
    return nlohmann::json::parse(in);
  }
  test::TempFolder folder{"tactile-workbench-live"};
};

TEST_F(WorkbenchLive, StreamSimIntoTheWorkbenchRecordsShowsAndClassifies) {
  // A model fitted on simulated fur touches.
  ASSERT_EQ(
      run_program("tactile",
                  "simulate --skin fur --subjects 3 --trials 1 --out " + folder.file("fur"), folder)
          .exit_code,
      0);
  ASSERT_EQ(run_program("tactile",
                        "features --pipeline fur --labels " + folder.file("fur/labels.db") +
                            " --out " + folder.file("fur.csv"),
                        folder)
                .exit_code,
            0);
  const CommandResult fitted =
      run_program("tactile",
                  "evaluate --features " + folder.file("fur.csv") +
                      " --classifier linear-svm --save-model " + folder.file("model.json"),
                  folder);
  ASSERT_EQ(fitted.exit_code, 0) << fitted.err;

  // The workbench listens first; the sender starts once it has drawn a frame, sends 20 s
  // of device time at 4x (5 s), and the script watches for 9 s.
  const std::string record = folder.file("session.h5");
  std::future<CommandResult> workbench = std::async(std::launch::async, [&] {
    return run_program(
        "tactile-workbench-headless",
        "--connect udp://:0 --skin fur --record " + record + " --model " +
            folder.file("model.json") + " --annotator ana --size 1200x800 --settings " +
            folder.file("settings.json") + " --script " +
            script("state @listening.json\nsleep 4\nscreenshot @live.png\nstate @during.json\n"
                   "key [\nsleep 1\nkey ]\nkey 1\nkey Enter\n"
                   "sleep 4\nstate @after.json\nkey Ctrl+R\nwait 2\nstate @stopped.json\n"),
        folder);
  });
  // The sender starts once the workbench has drawn a frame (it listens from before its first),
  // not after a guessed second: a slow start (a sanitizer build on a busy machine) lost the
  // first datagrams and left the script's first look at 52 samples.
  const auto listening = folder.file("listening.json");
  for (int waited = 0; waited < 600 && !std::filesystem::exists(listening); ++waited)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ASSERT_TRUE(std::filesystem::exists(listening)) << "the workbench drew no frame in 30 s";
  // It listens on the port the system gave it (asked for port 0), and says which.
  const nlohmann::json listening_state = state("listening.json");
  ASSERT_TRUE(listening_state["live"]["listening"].is_string()) << listening_state["live"].dump();
  const std::string url = listening_state["live"]["listening"].get<std::string>();
  EXPECT_EQ(url.rfind("udp://127.0.0.1:", 0), 0u) << url;
  EXPECT_NE(url, "udp://127.0.0.1:0");
  const CommandResult sent = run_program(
      "tactile", "stream-sim --skin fur --to " + url + " --rate-factor 4 --duration 20", folder);
  ASSERT_EQ(sent.exit_code, 0) << sent.err;
  ASSERT_EQ(workbench.wait_for(std::chrono::seconds(60)), std::future_status::ready);
  const CommandResult shown = workbench.get();
  ASSERT_EQ(shown.exit_code, 0) << shown.err << shown.out;

  // While streaming: samples arrived, none lost, the skin drawn with many colours.
  const nlohmann::json during = state("during.json");
  ASSERT_TRUE(during["live"].is_object()) << during.dump(2);
  EXPECT_GT(during["live"]["samples"].get<int>(), 60);
  EXPECT_EQ(during["live"]["lost"], 0);
  EXPECT_EQ(during["live"]["broken"], 0);
  EXPECT_EQ(during["live"]["recording"], record);
  const Png png = read_png(folder.file("live.png"));
  const nlohmann::json skin = during["views"]["skin"];
  const int x0 = skin["x"].get<int>(), y0 = skin["y"].get<int>();
  EXPECT_GT(
      colours_in(png, x0, y0 + 40, x0 + skin["width"].get<int>(), y0 + skin["height"].get<int>()),
      6u)
      << "the skin view is not lit";

  // Online decisions, "no touch" between touches and a class of the model during them.
  const nlohmann::json after = state("after.json");
  const nlohmann::json predictions = after["live"]["predictions"];
  ASSERT_FALSE(predictions.empty());
  std::set<std::string> classes;
  for (const nlohmann::json& decision : predictions)
    classes.insert(decision["class"].get<std::string>());
  EXPECT_EQ(after["live"]["model"], folder.file("model.json"));

  // The label made while recording is in the recording's label database.
  const nlohmann::json stopped = state("stopped.json");
  EXPECT_TRUE(stopped["live"]["recording"].is_null());
  ASSERT_EQ(stopped["live"]["recorded"].size(), 1u);
  RecordingFile file(record);
  EXPECT_FALSE(file.cut_off());
  EXPECT_EQ(file.layout_id(), "fur");
  EXPECT_GT(file.stream("skin").sample_count, 100);
  LabelStore store(folder.file("labels.db"));
  LabelFilter filter;
  filter.recording = "session";
  const std::vector<Label> labels = store.list(filter);
  ASSERT_EQ(labels.size(), 1u);
  EXPECT_EQ(labels.front().annotator, "ana");
  EXPECT_GT(labels.front().t1, labels.front().t0);
}

// The live skin's colour scale is learnt again as the stream arrives, over the whole buffer as a
// replay learns it over the whole file (issue 41: learnt once from the first two seconds, it read
// "rest ... +1" where the replay of the same samples read +198, and lit other taxels): at the
// end of a recorded session the two scales' tops agree, and so do the taxels drawn as touched.
TEST_F(WorkbenchLive, TheLiveColourScaleIsTheReplaysOfTheSameSamples) {
  const std::string record = folder.file("session.h5");
  const CommandResult shown =
      run_program("tactile-workbench-headless",
                  "--connect sim://fur?seed=3 --record " + record + " --size 1280x720 --settings " +
                      folder.file("settings.json") + " --script " +
                      script("sleep 7\nstate @live.json\nkey Ctrl+R\nwait 2\n"),
                  folder);
  ASSERT_EQ(shown.exit_code, 0) << shown.err;
  const nlohmann::json live = state("live.json");
  const double time = live["time"];
  const CommandResult replayed = run_program(
      "tactile-workbench-headless",
      record + " --time " + std::to_string(time) + " --size 1280x720 --settings " +
          folder.file("settings.json") + " --script " + script("wait 2\nstate @replay.json\n"),
      folder);
  ASSERT_EQ(replayed.exit_code, 0) << replayed.err;
  const nlohmann::json replay = state("replay.json");
  const double live_top = live["skin"]["scale"]["max"], replay_top = replay["skin"]["scale"]["max"];
  EXPECT_GT(replay_top, 20.0) << "the session holds no touch to scale by";
  EXPECT_NEAR(live_top / replay_top, 1.0, 0.3)
      << live_top << " live, " << replay_top << " replayed";
  EXPECT_NEAR(replay["time"].get<double>(), time, 1e-3);
  EXPECT_EQ(live["skin"]["touched"], replay["skin"]["touched"]);
}

// A camera beside the live skin (FFmpeg's lavfi test source standing in for a device): shown in
// the video view, stamped on the stream's clock, and recorded beside the recording from its
// pre-trigger on, attached with the offset of its first frame (docs/VIDEO.md, "Live camera").
TEST_F(WorkbenchLive, ACameraIsShownAndRecordedBesideTheSkinOnTheStreamsClock) {
  const CommandResult shown = run_program(
      "tactile-workbench-headless",
      "--connect sim://fur?seed=3 --camera lavfi:testsrc2=size=160x120:rate=15,realtime "
      "--pretrigger 1 --size 1280x720 --settings " +
          folder.file("settings.json") + " --script " +
          script("sleep 3\nstate @live.json\nscreenshot @live.png\nkey Ctrl+R\nsleep 3\n"
                 "key Ctrl+R\nwait 2\nstate @stopped.json\n"),
      folder);
  ASSERT_EQ(shown.exit_code, 0) << shown.err;
  const nlohmann::json live = state("live.json");
  const nlohmann::json& camera = live["live"]["camera"];
  ASSERT_FALSE(camera.is_null()) << live["live"];
  EXPECT_EQ(camera["error"], "");
  EXPECT_GT(camera["received"].get<int>(), 10);
  // Stamped on the stream's clock: the newest frame is within a second of the newest sample.
  ASSERT_FALSE(camera["frame_time"].is_null());
  EXPECT_NEAR(camera["frame_time"].get<double>(), live["live"]["newest"].get<double>(), 1.0);
  // Drawn: testsrc2's colour bars fill the camera's picture.
  const nlohmann::json box = live["boxes"]["video:picture:camera"];
  ASSERT_FALSE(box.is_null());
  const Png png = read_png(folder.file("live.png"));
  ASSERT_TRUE(png.pixels);
  EXPECT_GT(colours_in(png, static_cast<int>(box["x"].get<double>()) + 1,
                       static_cast<int>(box["y"].get<double>()) + 1,
                       static_cast<int>(box["x"].get<double>() + box["width"].get<double>()) - 1,
                       static_cast<int>(box["y"].get<double>() + box["height"].get<double>()) - 1),
            6u);

  // The recording has its camera video beside it, which begins with the pre-trigger.
  const nlohmann::json stopped = state("stopped.json");
  ASSERT_EQ(stopped["live"]["recorded"].size(), 1u) << stopped["error"];
  const std::string recording = stopped["live"]["recorded"][0];
  const std::vector<VideoAttachment> attachments = read_attachments(recording);
  ASSERT_EQ(attachments.size(), 1u);
  EXPECT_EQ(attachments[0].name, "camera");
  const RecordingFile file(recording);
  const StreamInfo& stream = file.streams().front();
  VideoFile video(video_path(recording, attachments[0]));
  EXPECT_GT(video.info().frame_count, 30);
  // Its first frame is no later than the recording's first sample (the pre-trigger's frames
  // come first), and it lasts to about the recording's end.
  EXPECT_LE(attachments[0].offset, stream.start_time + 0.2);
  EXPECT_GE(attachments[0].offset, stream.start_time - 1.5);
  EXPECT_NEAR(attachments[0].offset + video.info().duration, stream.start_time + stream.duration(),
              0.7);
}

// While following, the plot moves to the channels being touched (a simulated NAO touches one
// side, then another), and before a recording exists the timeline says where labels will go.
TEST_F(WorkbenchLive, ThePlotFollowsTheActiveChannels) {
  const CommandResult shown = run_program(
      "tactile-workbench-headless",
      "--connect sim://nao?seed=3 --annotator ana --size 1280x720 --settings " +
          folder.file("settings.json") + " --script " +
          script("sleep 2.5\nstate @a.json\nsleep 2\nstate @b.json\nsleep 2\nstate @c.json\n"
                 "sleep 2\nstate @d.json\n"),
      folder);
  ASSERT_EQ(shown.exit_code, 0) << shown.err;
  std::set<std::string> seen;
  for (const char* name : {"a.json", "b.json", "c.json", "d.json"}) {
    const nlohmann::json at = state(name);
    EXPECT_FALSE(at["plotted"].empty()) << name;
    EXPECT_LE(at["plotted"].size(), 8u) << name;
    seen.insert(at["plotted"].dump());
  }
  EXPECT_GE(seen.size(), 2u) << "the plotted channels never changed while the skin was touched";
}

// A serial device (a pty behind a stable symlink) unplugged while the workbench shows it and
// records: `state` says it is gone and which path is waited for, the session goes on, and
// once it is plugged back the stream resumes, the unplug counted and the recording whole.
TEST_F(WorkbenchLive, AnUnpluggedSerialDeviceIsWaitedForShownAndResumes) {
  const std::string link = folder.file("usb-fur-if00");
  int master = -1;
  const auto plug = [&] {
    // Not inherited by the workbench: a copy of the master there would keep the port up.
    master = posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
    ASSERT_GE(master, 0);
    ASSERT_EQ(grantpt(master), 0);
    ASSERT_EQ(unlockpt(master), 0);
    ASSERT_EQ(symlink(ptsname(master), link.c_str()), 0);
  };
  plug();
  const SkinLayout layout = load_layout("fur");
  SimulationOptions options;
  options.subjects = 1;
  const Stream stream =
      skin_record("fur").simulate(layout, options, 0, 0).recording.streams.front();
  uint32_t sequence = 0;
  const auto datagrams = PacketEncoder(layout, stream).encode(0, 15, sequence);  // a second
  const auto send = [&] {
    for (const auto& datagram : datagrams)
      ASSERT_EQ(write(master, datagram.data(), datagram.size()),
                static_cast<ssize_t>(datagram.size()));
  };
  const std::string record = folder.file("unplugged.h5");
  std::future<CommandResult> workbench = std::async(std::launch::async, [&] {
    return run_program(
        "tactile-workbench-headless",
        "--connect serial://" + link + " --skin fur --record " + record +
            " --size 1000x700 --settings " + folder.file("settings.json") + " --script " +
            script("state @open.json\nsleep 2\nstate @gone.json\nsleep 3\nstate @back.json\n"),
        folder);
  });
  const auto appears = [&](const std::string& name) {
    for (int waited = 0; waited < 600 && !std::filesystem::exists(folder.file(name)); ++waited)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    return std::filesystem::exists(folder.file(name));
  };
  ASSERT_TRUE(appears("open.json")) << "the workbench drew no frame in 30 s";
  send();
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  close(master);  // unplugged
  unlink(link.c_str());
  ASSERT_TRUE(appears("gone.json"));
  plug();  // plugged back; the workbench reopens the path within 0.25 s
  std::this_thread::sleep_for(std::chrono::milliseconds(800));
  send();  // the device started over: the same numbers and times again
  ASSERT_EQ(workbench.wait_for(std::chrono::seconds(60)), std::future_status::ready);
  const CommandResult shown = workbench.get();
  close(master);
  unlink(link.c_str());
  ASSERT_EQ(shown.exit_code, 0) << shown.err << shown.out;

  const nlohmann::json gone = state("gone.json")["live"];
  EXPECT_NE(gone["gone"].get<std::string>().find(link), std::string::npos) << gone.dump();
  EXPECT_EQ(gone["unplugs"], 1);
  EXPECT_EQ(gone["failure"], "");
  EXPECT_EQ(gone["received"], 15);
  const nlohmann::json back = state("back.json")["live"];
  EXPECT_EQ(back["gone"], "") << back.dump();
  EXPECT_EQ(back["unplugs"], 1);
  EXPECT_EQ(back["replugs"], 1);
  EXPECT_EQ(back["restarts"], 1);
  EXPECT_EQ(back["received"], 30);
  EXPECT_EQ(back["lost"], 0);
  EXPECT_EQ(back["duplicated"], 0);
  EXPECT_GE(back["gap_samples"], 15);  // away for more than a second at 15 Hz
  EXPECT_EQ(back["samples"], 30 + back["gap_samples"].get<int64_t>());
  // The recording holds both seconds and the gap between (finished when the script ended).
  const RecordingFile file(record);
  EXPECT_EQ(file.streams().front().sample_count, back["samples"].get<int64_t>());
}

TEST_F(WorkbenchLive, RefusesABadSourceWithTheReason) {
  const CommandResult refused =
      run_program("tactile-workbench-headless",
                  "--connect tcp://x:1 --screenshot " + folder.file("x.png") + " --settings " +
                      folder.file("settings.json"),
                  folder);
  EXPECT_NE(refused.exit_code, 0);
  EXPECT_NE(refused.err.find("not a live source kind"), std::string::npos) << refused.err;
  const CommandResult no_skin =
      run_program("tactile-workbench-headless",
                  "--connect udp://:9 --screenshot " + folder.file("x.png") + " --settings " +
                      folder.file("settings.json"),
                  folder);
  EXPECT_NE(no_skin.exit_code, 0);
  EXPECT_NE(no_skin.err.find("--skin"), std::string::npos) << no_skin.err;
  const CommandResult both =
      run_program("tactile-workbench-headless",
                  "a.h5 --connect sim://fur --screenshot " + folder.file("x.png"), folder);
  EXPECT_NE(both.exit_code, 0);
}

}  // namespace
}  // namespace tactile
