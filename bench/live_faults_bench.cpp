// Devices that go away and come back (issue 27), with recording on. Three kinds of run:
//
//   unplug   a serial device (a pseudo-terminal behind a symlink, as /dev/serial/by-id/...)
//            unplugged at a different point of the stream each run (whole datagrams, or in
//            the middle of one), away for 0.3-0.75 s, plugged back; half the runs the device
//            restarts (count and clock from 0), half it kept counting while away;
//   restart  a UDP sender that stops for 0.5-1.7 s and starts again from 0;
//   jump     a UDP sender whose clock steps (an hour forward, back, to 0, +0.5 s, -0.1 s).
//
// Each run is its own process, so a crash is counted, not fatal. In each, the receiver feeds
// a LiveSampleSource and a LiveRecorder writes a temporary file, driven by a "UI" loop every
// 16 ms (ring drain, counters(), recorder take), whose longest call is measured. After each:
// the file passes verify_recording, every sample that arrived before the fault is in it
// exactly as sent, the samples after it follow, and what lies between is a gap (NaN).
//
//   build/bench/live_faults_bench [--unplugs N] [--restarts N] [--jumps N]
// Prints a markdown table (bench/FAULTS.md, "Devices that go away").
#include <fcntl.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

#include "tactile/error.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/live/live_input.h"
#include "tactile/live/live_receiver.h"
#include "tactile/live/live_recorder.h"
#include "tactile/live/live_source.h"
#include "tactile/live/packets.h"
#include "tactile/live/udp.h"
#include "tactile/skins/skin.h"
#include "tactile/verify/verify.h"

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace tactile {
namespace {

constexpr const char* kSkin = "nao";  // 250 datagrams a second of one sample
constexpr double kRate = 250.0;

enum class Kind { kUnplug, kRestart, kJump };

// What a run reports to the parent through a pipe (plain bytes).
struct RunResult {
  int completed = 0;             // 1 when the run got to the end
  int64_t before_sent = 0;       // samples that arrived before the fault
  int64_t before_in_file = 0;    // ... found in the file, exactly as sent and in place
  int64_t after_sent = 0;        // samples sent after the fault
  int64_t after_in_file = 0;     // ... found in the file after the gap
  int64_t gap_samples = 0;       // NaN rows between them
  int64_t stray = 0;             // rows in the gap that are not NaN, or rows beyond
  double away_seconds = 0.0;     // how long the device or sender was away (0 for jumps)
  double silence_seconds = 0.0;  // from the last datagram sent before the fault to the first after
  int64_t verify_problems = 0;
  double longest_ui_ms = 0.0;
  int64_t unplugs = 0, replugs = 0, restarts = 0, stalls = 0, clock_jumps = 0;
  int64_t lost = 0, duplicated = 0, reordered = 0, broken = 0;
  char note[240] = {};
};

void set_note(RunResult& result, const std::string& text) {
  std::snprintf(result.note, sizeof result.note, "%s", text.c_str());
}

// A simulated stream of the skin, `count` samples from device time 0 (its trials repeated).
Stream long_stream(const SkinLayout& layout, int64_t count) {
  SimulationOptions options;
  options.subjects = 1;
  SimulatedTrial trial = skin_record(kSkin).simulate(layout, options, 0, 0);
  auto& streams = trial.recording.streams;
  auto skin = std::find_if(streams.begin(), streams.end(),
                           [](const Stream& s) { return s.name == "skin"; });
  Stream stream = std::move(skin != streams.end() ? *skin : streams.front());
  const SampleMatrix one = stream.samples;
  stream.samples.resize(count, one.cols());
  for (int64_t row = 0; row < count; ++row) stream.samples.row(row) = one.row(row % one.rows());
  stream.timestamps.clear();
  stream.start_time = 0.0;
  return stream;
}

void set_device_time(std::vector<uint8_t>& datagram, double time) {
  std::memcpy(datagram.data() + 12, &time, 8);
}

// The rows a datagram carries, as the receiver decodes them.
SampleMatrix decoded_rows(const std::vector<std::vector<uint8_t>>& datagrams,
                          const SkinLayout& layout) {
  std::vector<SampleMatrix> parts;
  int64_t rows = 0;
  for (const auto& datagram : datagrams) {
    parts.push_back(decode_packet(datagram, layout).samples);
    rows += parts.back().rows();
  }
  SampleMatrix all(rows, parts.empty() ? 0 : parts.front().cols());
  int64_t at = 0;
  for (const SampleMatrix& part : parts) {
    all.middleRows(at, part.rows()) = part;
    at += part.rows();
  }
  return all;
}

class Pty {
 public:
  explicit Pty(std::string link) : link_(std::move(link)) { plug(); }
  ~Pty() { unplug(); }
  void plug() {
    master_ = posix_openpt(O_RDWR | O_NOCTTY);
    if (master_ < 0 || grantpt(master_) != 0 || unlockpt(master_) != 0)
      throw Error("pty", "cannot open");
    if (symlink(ptsname(master_), link_.c_str()) != 0) throw Error(link_, "cannot link");
  }
  void unplug() {
    if (master_ < 0) return;
    close(master_);
    master_ = -1;
    unlink(link_.c_str());
  }
  void send(const uint8_t* bytes, size_t size) {
    while (size > 0) {
      const ssize_t written = write(master_, bytes, size);
      if (written <= 0) throw Error("pty", "write failed");
      bytes += written;
      size -= static_cast<size_t>(written);
    }
  }

 private:
  std::string link_;
  int master_ = -1;
};

// The receiving side's counters as the UI loop last saw them.
struct Seen {
  std::atomic<int64_t> datagrams{0};
  std::atomic<int64_t> replugs{0};
  std::atomic<bool> done{false};
  std::atomic<bool> failed{false};
};

// Waits until `condition` holds or 10 s pass; false then.
template <typename Condition>
bool wait_for(Condition condition) {
  const auto end = Clock::now() + std::chrono::seconds(10);
  while (!condition()) {
    if (Clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return true;
}

// Sends datagrams paced at the device's rate from `begin`.
template <typename Send>
void paced(const std::vector<std::vector<uint8_t>>& datagrams, double rate, Send send) {
  const auto begin = Clock::now();
  for (size_t k = 0; k < datagrams.size(); ++k) {
    std::this_thread::sleep_until(
        begin + std::chrono::duration_cast<Clock::duration>(
                    std::chrono::duration<double>(static_cast<double>(k) / rate)));
    send(datagrams[k]);
  }
}

RunResult run_one(Kind kind, int run, const std::string& folder) {
  RunResult result;
  const SkinLayout layout = load_layout(kSkin);
  const PacketFormatInfo format = packet_format_info(kSkin);
  const double rate = format.datagrams_per_second();

  // The scenario: what is sent before the fault, after it, and the fault itself.
  int64_t fault_at = 0, after = 125;
  double away = 0.0;
  bool restart = true, cut = false;
  if (kind == Kind::kUnplug) {
    fault_at = 20 + (run * 97) % 480;  // 20 ... 499 datagrams: a different point each run
    cut = run % 3 == 2;                // then half a datagram more, cut by the unplug
    away = 0.3 + 0.05 * (run % 10);
    restart = run % 2 == 0;  // else the device kept counting while away
  } else if (kind == Kind::kRestart) {
    fault_at = 100 + 50 * run;
    away = 0.5 + 0.3 * run;
  } else {
    fault_at = 100 + 20 * run;
    after = 200;
  }
  const int64_t missed = restart ? 0 : std::llround(away * rate);
  const Stream stream = long_stream(layout, fault_at + 1 + missed + after);
  const PacketEncoder encoder(layout, stream);
  uint32_t sequence = 0;
  std::vector<std::vector<uint8_t>> before = encoder.encode(0, fault_at + 1, sequence);
  const std::vector<uint8_t> cut_datagram = before.back();
  before.pop_back();
  std::vector<std::vector<uint8_t>> later;
  if (kind == Kind::kJump) {
    sequence = static_cast<uint32_t>(fault_at);
    later = encoder.encode(fault_at, after, sequence);
    const double steps[] = {3600.0, -50.0, 0.0, 0.5, -0.1};
    for (auto& datagram : later) {
      const PacketHeader header = decode_packet_header(datagram);
      // Step 2 sets the clock to 0 at the jump: the rest count from there.
      const double time = run % 5 == 2
                              ? header.time - static_cast<double>(fault_at) / format.sample_rate_hz
                              : header.time + steps[run % 5];
      set_device_time(datagram, time);
    }
  } else if (restart) {
    sequence = 0;
    later = encoder.encode(0, after, sequence);
  } else {
    sequence = static_cast<uint32_t>(fault_at + 1 + missed);
    later = encoder.encode(fault_at + 1 + missed, after, sequence);
  }
  const SampleMatrix before_rows = decoded_rows(before, layout);
  const SampleMatrix later_rows = decoded_rows(later, layout);
  result.before_sent = before_rows.rows();
  result.after_sent = later_rows.rows();
  result.away_seconds = away;

  // The receiving end, with the input opened before anything is sent.
  std::unique_ptr<Pty> pty;
  std::unique_ptr<UdpSocket> sender;
  uint16_t port = 0;
  std::unique_ptr<DatagramInput> input;
  if (kind == Kind::kUnplug) {
    const std::string link = folder + "/usb-tactile-if00";
    pty = std::make_unique<Pty>(link);
    input = open_live_input(parse_live_address("serial://" + link, "--connect"));
  } else {
    {
      UdpSocket probe = UdpSocket::bind_to({"127.0.0.1", 0});
      port = probe.local_port();
    }
    input = open_live_input(parse_live_address("udp://:" + std::to_string(port), "--connect"));
  }
  LiveReceiver receiver(std::move(input), layout);
  LiveSampleSource source(receiver.source_info(),
                          static_cast<int64_t>(600 * format.sample_rate_hz));
  std::unique_ptr<LiveRecorder> recorder;
  const std::string path = folder + "/run.h5";
  Seen seen;

  std::thread device([&] {
    try {
      const auto send = [&](const std::vector<uint8_t>& datagram) {
        if (pty)
          pty->send(datagram.data(), datagram.size());
        else
          sender->send(datagram);
      };
      if (!pty) sender = std::make_unique<UdpSocket>(UdpSocket::connect_to({"127.0.0.1", port}));
      if (kind == Kind::kJump) {
        std::vector<std::vector<uint8_t>> all = before;
        all.insert(all.end(), later.begin(), later.end());
        paced(all, rate, send);
      } else {
        paced(before, rate, send);
        const auto last_sent = Clock::now();
        if (cut) pty->send(cut_datagram.data(), cut_datagram.size() / 2);
        if (!wait_for([&] { return seen.datagrams >= fault_at; }))
          throw Error("run", "datagrams before the fault never all arrived");
        if (pty) {
          pty->unplug();
          std::this_thread::sleep_for(std::chrono::duration<double>(away));
          pty->plug();
          if (!wait_for([&] { return seen.replugs >= 1; }))
            throw Error("run", "the device was never reopened");
        } else {
          sender.reset();  // the sender process ends ...
          std::this_thread::sleep_for(std::chrono::duration<double>(away));
          sender = std::make_unique<UdpSocket>(
              UdpSocket::connect_to({"127.0.0.1", port}));  // ... and a new one starts
        }
        result.silence_seconds = std::chrono::duration<double>(Clock::now() - last_sent).count();
        paced(later, rate, send);
      }
      const int64_t total = static_cast<int64_t>(before.size() + later.size());
      if (!wait_for([&] { return seen.datagrams >= total; }))
        throw Error("run", "datagrams after the fault never all arrived");
    } catch (const std::exception& error) {
      set_note(result, error.what());
      seen.failed = true;
    }
    seen.done = true;
  });

  // The UI: a frame's worth of live work every 16 ms.
  while (!seen.done) {
    const auto begin = Clock::now();
    receiver.ring().drain(
        [&](double time, std::span<const float> values) { source.add(time, values); });
    const LiveCounters counters = receiver.counters();
    if (!recorder && source.sample_count() > 0) {
      LiveRecorderOptions options;
      options.pretrigger_seconds = 600.0;  // from the first sample
      recorder = std::make_unique<LiveRecorder>(path, source, options);
    }
    if (recorder) recorder->take(source);
    const double took = std::chrono::duration<double, std::milli>(Clock::now() - begin).count();
    result.longest_ui_ms = std::max(result.longest_ui_ms, took);
    seen.datagrams = counters.datagrams;
    seen.replugs = counters.replugs;
    std::this_thread::sleep_for(std::chrono::milliseconds(16));
  }
  device.join();
  receiver.stop();
  receiver.ring().drain(
      [&](double time, std::span<const float> values) { source.add(time, values); });
  const LiveCounters counters = receiver.counters();
  result.unplugs = counters.unplugs;
  result.replugs = counters.replugs;
  result.restarts = counters.restarts;
  result.stalls = counters.stalls;
  result.clock_jumps = counters.clock_jumps;
  result.lost = counters.lost;
  result.duplicated = counters.duplicated;
  result.reordered = counters.reordered;
  result.broken = counters.broken;
  if (seen.failed || !recorder) {
    if (!recorder) set_note(result, "nothing was recorded");
    return result;
  }
  recorder->finish(source);
  recorder.reset();
  const std::vector<FileProblem> problems = verify_recording(path);
  result.verify_problems = static_cast<int64_t>(problems.size());
  if (!problems.empty()) set_note(result, problems.front().message);

  // The file against what was sent.
  const RecordingFile file(path);
  const int64_t rows = file.streams().front().sample_count;
  const SampleMatrix written = file.read(file.streams().front().name, 0, rows);
  const int64_t first = std::min(rows, before_rows.rows());
  for (int64_t row = 0; row < first; ++row)
    if (written.row(row) == before_rows.row(row)) ++result.before_in_file;
  const int64_t later_from = rows - later_rows.rows();
  if (later_from >= first) {
    for (int64_t row = 0; row < later_rows.rows(); ++row)
      if (written.row(later_from + row) == later_rows.row(row)) ++result.after_in_file;
    result.gap_samples = later_from - first;
    for (int64_t row = first; row < later_from; ++row)
      if (!written.row(row).array().isNaN().all()) ++result.stray;
  }
  result.completed = 1;
  return result;
}

// Runs `run_one` in a child process; a crash or a hang (60 s) comes back as completed = 0
// with the reason in the note.
RunResult run_isolated(Kind kind, int run) {
  const fs::path folder = fs::temp_directory_path() /
                          ("tactile-faults-" + std::to_string(getpid()) + "-" +
                           std::to_string(run) + "-" + std::to_string(static_cast<int>(kind)));
  fs::create_directories(folder);
  int pipe_ends[2];
  if (pipe(pipe_ends) != 0) throw Error("bench", "no pipe");
  const pid_t child = fork();
  if (child == 0) {
    close(pipe_ends[0]);
    alarm(60);
    RunResult result;
    try {
      result = run_one(kind, run, folder.string());
    } catch (const std::exception& error) {
      set_note(result, error.what());
    }
    const ssize_t written = write(pipe_ends[1], &result, sizeof result);
    _exit(written == sizeof result ? 0 : 3);
  }
  close(pipe_ends[1]);
  RunResult result;
  const ssize_t got = read(pipe_ends[0], &result, sizeof result);
  close(pipe_ends[0]);
  int status = 0;
  waitpid(child, &status, 0);
  if (got != sizeof result || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    result = RunResult{};
    set_note(result, WIFSIGNALED(status) ? "crashed: signal " + std::to_string(WTERMSIG(status))
                                         : "no result");
  }
  fs::remove_all(folder);
  return result;
}

struct Row {
  std::string name;
  std::vector<RunResult> runs;
};

void print_table(const std::vector<Row>& rows) {
  std::cout
      << "| fault | runs | crashes or hangs | samples before the fault in the file | after it in "
         "the file | "
         "gap in the file / sender's silence | verify problems | counted | longest UI-side call |\n"
      << "|---|---|---|---|---|---|---|---|---|\n";
  for (const Row& row : rows) {
    int64_t crashed = 0, before_sent = 0, before_in = 0, after_sent = 0, after_in = 0, problems = 0,
            stray = 0;
    int64_t unplugs = 0, replugs = 0, restarts = 0, stalls = 0, jumps = 0, lost = 0, duplicated = 0,
            reordered = 0, broken = 0;
    double longest = 0.0, gap_min = 1e18, gap_max = 0.0, silence_min = 1e18, silence_max = 0.0;
    for (const RunResult& run : row.runs) {
      if (!run.completed) {
        ++crashed;
        std::cerr << row.name << ": " << run.note << "\n";
        continue;
      }
      if (run.verify_problems > 0) std::cerr << row.name << ": " << run.note << "\n";
      before_sent += run.before_sent;
      before_in += run.before_in_file;
      after_sent += run.after_sent;
      after_in += run.after_in_file;
      problems += run.verify_problems;
      stray += run.stray;
      unplugs += run.unplugs;
      replugs += run.replugs;
      restarts += run.restarts;
      stalls += run.stalls;
      jumps += run.clock_jumps;
      lost += run.lost;
      duplicated += run.duplicated;
      reordered += run.reordered;
      broken += run.broken;
      longest = std::max(longest, run.longest_ui_ms);
      const double gap = static_cast<double>(run.gap_samples) / kRate;
      gap_min = std::min(gap_min, gap);
      gap_max = std::max(gap_max, gap);
      silence_min = std::min(silence_min, run.silence_seconds);
      silence_max = std::max(silence_max, run.silence_seconds);
    }
    char gap[120];
    std::snprintf(gap, sizeof gap, "%.2f-%.2f s / %.2f-%.2f s%s", gap_min, gap_max, silence_min,
                  silence_max, stray > 0 ? " (NOT all NaN)" : "");
    char counted[200];
    std::snprintf(
        counted, sizeof counted,
        "unplugs %lld, replugs %lld, restarts %lld, stalls %lld, clock jumps %lld; lost %lld, "
        "duplicated %lld, reordered %lld, broken %lld",
        static_cast<long long>(unplugs), static_cast<long long>(replugs),
        static_cast<long long>(restarts), static_cast<long long>(stalls),
        static_cast<long long>(jumps), static_cast<long long>(lost),
        static_cast<long long>(duplicated), static_cast<long long>(reordered),
        static_cast<long long>(broken));
    char longest_text[32];
    std::snprintf(longest_text, sizeof longest_text, "%.1f ms", longest);
    std::cout << "| " << row.name << " | " << row.runs.size() << " | " << crashed << " | "
              << before_in << " / " << before_sent << " | " << after_in << " / " << after_sent
              << " | " << gap << " | " << problems << " | " << counted << " | " << longest_text
              << " |\n";
  }
}

}  // namespace
}  // namespace tactile

int main(int argc, char** argv) {
  using namespace tactile;
  int unplugs = 24, restarts = 5, jumps = 5;
  for (int k = 1; k + 1 < argc; k += 2) {
    const std::string option = argv[k];
    const int value = std::atoi(argv[k + 1]);
    if (option == "--unplugs")
      unplugs = value;
    else if (option == "--restarts")
      restarts = value;
    else if (option == "--jumps")
      jumps = value;
  }
  std::vector<Row> rows = {{"serial unplug/replug, device restarts (count and clock from 0)", {}},
                           {"serial unplug/replug, device kept counting while away", {}},
                           {"serial unplug/replug in the middle of a datagram", {}},
                           {"UDP sender stopped and restarted from 0", {}},
                           {"UDP sender clock jumps (+1 h, -50 s, to 0, +0.5 s, -0.1 s)", {}}};
  const auto began = Clock::now();
  for (int run = 0; run < unplugs; ++run) {
    const RunResult result = run_isolated(Kind::kUnplug, run);
    rows[run % 3 == 2 ? 2 : run % 2 == 0 ? 0 : 1].runs.push_back(result);
    std::cerr << "unplug run " << run << (result.completed ? " done" : " FAILED") << "\n";
  }
  for (int run = 0; run < restarts; ++run)
    rows[3].runs.push_back(run_isolated(Kind::kRestart, run));
  for (int run = 0; run < jumps; ++run) rows[4].runs.push_back(run_isolated(Kind::kJump, run));
  std::cout << "Skin " << kSkin << " (250 datagrams/s), recording on; " << unplugs
            << " unplug points ("
            << "20-499 datagrams into the stream), each run in its own process; "
            << std::chrono::duration<double>(Clock::now() - began).count() << " s in all.\n\n";
  print_table(rows);
  return 0;
}
