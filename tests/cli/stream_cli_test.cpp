// `tactile stream-sim` and `tactile stream-listen` end to end on loopback: a listener in the
// background, a one-second simulated stream, the count and loss it reports, the recording it
// writes, and the URLs both refuse. Every wait is bounded.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <future>
#include <nlohmann/json.hpp>
#include <regex>
#include <thread>

#include "cli_test_support.h"

namespace tactile {
namespace {

using test::CommandResult;
using test::run_program;
using test::TempFolder;

// The address a listener started on port 0 says it got (its --bound-to file), once it says
// so; "" if it has not within `timeout` (it failed to start: its error tells why).
std::string bound_address(const std::string& file, std::chrono::seconds timeout) {
  const auto end = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < end) {
    std::ifstream in(file);
    std::string url;
    if (in && std::getline(in, url) && !url.empty()) return url;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return "";
}

// The number after "key: " in a command's report, -1 when absent.
double reported(const std::string& text, const std::string& key) {
  std::smatch match;
  if (!std::regex_search(text, match, std::regex("(^|\n)" + key + ": ([0-9.]+)"))) return -1;
  return std::stod(match[2]);
}

struct Session {
  CommandResult sender;
  CommandResult listener;
};

// Starts stream-listen in the background, streams one second of `skin` at the device's rate,
// and waits for the listener to fall silent (at most 30 s).
Session stream_one_second(const std::string& skin, const std::string& out,
                          const TempFolder& listen_folder, const TempFolder& send_folder) {
  const std::string bound = listen_folder.file("bound.txt");
  std::future<CommandResult> listening = std::async(std::launch::async, [&] {
    return run_program("tactile",
                       "stream-listen --skin " + skin +
                           " --from udp://127.0.0.1:0 --duration 30 --idle 2 --bound-to '" + bound +
                           "'" + (out.empty() ? "" : " --out '" + out + "'"),
                       listen_folder);
  });
  Session session;
  const std::string url = bound_address(bound, std::chrono::seconds(30));
  if (url.empty()) {
    session.listener = listening.get();
    ADD_FAILURE() << "the listener never said where it listens: " << session.listener.err;
    return session;
  }
  session.sender = run_program(
      "tactile", "stream-sim --skin " + skin + " --to " + url + " --rate-factor 1 --duration 1",
      send_folder);
  session.listener = listening.get();
  return session;
}

class StreamCli : public ::testing::TestWithParam<std::pair<std::string, int>> {};

TEST_P(StreamCli, OneSecondOnLoopbackArrivesCompleteAtTheDeviceRate) {
  const auto& [skin, datagrams_per_second] = GetParam();
  const TempFolder listen_folder("tactile-listen"), send_folder("tactile-send");
  const std::string out = listen_folder.file(skin + "-live.h5");
  const Session session = stream_one_second(skin, out, listen_folder, send_folder);
  ASSERT_EQ(session.sender.exit_code, 0) << session.sender.err;
  ASSERT_EQ(session.listener.exit_code, 0) << session.listener.err;
  const std::string& sent = session.sender.out;
  const std::string& heard = session.listener.out;

  EXPECT_EQ(reported(sent, "datagrams"), datagrams_per_second) << sent;
  EXPECT_EQ(reported(heard, "datagrams"), datagrams_per_second) << heard;
  EXPECT_EQ(reported(heard, "bytes"), reported(sent, "bytes"));
  EXPECT_EQ(reported(heard, "lost"), 0) << heard;
  EXPECT_EQ(reported(heard, "broken"), 0) << heard;
  EXPECT_EQ(reported(heard, "reordered"), 0) << heard;
  // Whether it was paced (about 1 s from the first datagram to the last) is a figure of time,
  // measured by bench/stream_pacing.sh, not asserted here.

  // What arrived was recorded: one second of samples at the device's rate.
  const TempFolder info_folder("tactile-info");
  const CommandResult info = run_program("tactile", "info --json '" + out + "'", info_folder);
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const nlohmann::json streams = nlohmann::json::parse(info.out)["streams"];
  ASSERT_EQ(streams.size(), 1u);
  EXPECT_EQ(streams[0]["samples"], reported(sent, "samples"));
  EXPECT_NEAR(streams[0]["duration_s"].get<double>(), 1.0, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Skins, StreamCli,
                         ::testing::Values(std::make_pair(std::string("nao"), 250),
                                           std::make_pair(std::string("fur"), 15),
                                           std::make_pair(std::string("flux"), 100)),
                         [](const auto& param_info) { return param_info.param.first; });

// A sender stopped and started again a second later counts from 0 with its clock from 0: the
// listener reports one restart and one stall, nothing lost, duplicated or reordered, and the
// recording holds both runs with the silence between them as a gap.
TEST(StreamCliFaults, ASenderRestartedAfterAPauseIsOneRestartAndOneStall) {
  const TempFolder listen_folder("tactile-listen-restart"), send_folder("tactile-send-restart");
  const std::string out = listen_folder.file("restarted.h5");
  const std::string bound = listen_folder.file("bound.txt");
  std::future<CommandResult> listening = std::async(std::launch::async, [&] {
    return run_program("tactile",
                       "stream-listen --skin fur --from udp://127.0.0.1:0 --bound-to '" + bound +
                           "' --duration 120 --datagrams 30 --json --out '" + out + "'",
                       listen_folder);
  });
  const std::string url = bound_address(bound, std::chrono::seconds(30));
  ASSERT_FALSE(url.empty()) << "the listener never said where it listens";
  // The listener ends at the 30th datagram, not after a silence: a slow machine (a sanitizer
  // build beside a compiler) may take seconds to start the second sender.
  for (int run = 0; run < 2; ++run) {
    if (run > 0) std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    const CommandResult sender = run_program(
        "tactile", "stream-sim --skin fur --to " + url + " --rate-factor 1 --duration 1",
        send_folder);
    ASSERT_EQ(sender.exit_code, 0) << sender.err;
  }
  const CommandResult listener = listening.get();
  ASSERT_EQ(listener.exit_code, 0) << listener.err;
  const nlohmann::json report = nlohmann::json::parse(listener.out);
  EXPECT_EQ(report["datagrams"], 30) << listener.out;
  EXPECT_EQ(report["restarts"], 1) << listener.out;
  EXPECT_EQ(report["stalls"], 1) << listener.out;
  EXPECT_EQ(report["lost"], 0) << listener.out;
  EXPECT_EQ(report["duplicated"], 0) << listener.out;
  EXPECT_EQ(report["reordered"], 0) << listener.out;
  EXPECT_EQ(report["clock_jumps"], 0) << listener.out;
  // Both seconds, in order, with at least the 1.5 s pause between them.
  EXPECT_EQ(report["samples"], 30);
  EXPECT_GT(report["end_time"].get<double>() - report["first_time"].get<double>(), 3.4);
  const TempFolder info_folder("tactile-info-restart");
  const CommandResult info = run_program("tactile", "info --json '" + out + "'", info_folder);
  ASSERT_EQ(info.exit_code, 0) << info.err;
  EXPECT_EQ(nlohmann::json::parse(info.out)["streams"][0]["samples"], 30);
}

TEST(StreamCliUrls, BadUrlsAndPortsAreRefusedNamingTheOption) {
  const TempFolder folder("tactile-urls");
  for (const std::string url : {"udp://127.0.0.1:65536", "http://127.0.0.1:9000", "udp://127.0.0.1",
                                "udp://127.0.0.1:port", "udp://nao.local:9000"}) {
    const CommandResult sim =
        run_program("tactile", "stream-sim --skin fur --to '" + url + "' --duration 1", folder);
    EXPECT_EQ(sim.exit_code, 1) << url;
    EXPECT_NE(sim.err.find("--to"), std::string::npos) << url << ": " << sim.err;
    const CommandResult listen = run_program(
        "tactile", "stream-listen --skin fur --from '" + url + "' --duration 1", folder);
    EXPECT_EQ(listen.exit_code, 1) << url;
    EXPECT_NE(listen.err.find("--from"), std::string::npos) << url << ": " << listen.err;
  }
  // Port 0 is a listener's "any free port", never a place to send to.
  const CommandResult nowhere =
      run_program("tactile", "stream-sim --skin fur --to udp://127.0.0.1:0 --duration 1", folder);
  EXPECT_EQ(nowhere.exit_code, 1);
  EXPECT_NE(nowhere.err.find("--to"), std::string::npos) << nowhere.err;
  const CommandResult port_range = run_program(
      "tactile", "stream-sim --skin fur --to udp://127.0.0.1:70000 --duration 1", folder);
  EXPECT_NE(port_range.err.find("1-65535"), std::string::npos) << port_range.err;
}

TEST(StreamCliUrls, UnknownSkinAndBadRateFactorAreRefused) {
  const TempFolder folder("tactile-skin");
  const CommandResult skin = run_program(
      "tactile", "stream-sim --skin grid:4x4 --to udp://127.0.0.1:9 --duration 1", folder);
  EXPECT_EQ(skin.exit_code, 1);
  EXPECT_NE(skin.err.find("grid:4x4"), std::string::npos) << skin.err;
  const CommandResult rate = run_program(
      "tactile", "stream-sim --skin fur --to udp://127.0.0.1:9 --rate-factor 0 --duration 1",
      folder);
  EXPECT_EQ(rate.exit_code, 1);
  EXPECT_NE(rate.err.find("--rate-factor"), std::string::npos) << rate.err;
}

}  // namespace
}  // namespace tactile
