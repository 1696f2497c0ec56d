// Live mode under load (issue "Live mode"), one run each, figures as counts and ratios:
//
//   live_bench ingest [FACTOR] [SECONDS]
//     The whole workbench drawn headless at 60 frames a second, connected over UDP loopback
//     to a sender (in this process, on its own thread) playing the simulated NAO skin at
//     FACTOR times its rate (default 10: 32 cells x 8 channels at 2.5 kHz) for SECONDS
//     (default 20). Prints datagrams sent, received, lost, broken, dropped at the hand-over,
//     frame times, and how far the skin was behind the newest datagram sent, in frames.
//
//   live_bench latency MODEL.json RECORDING.h5 LABELS.db [SECONDS]
//     Replays the recording at 1x through the live path (receiver, buffer, online
//     classifier, as the workbench runs them), and for each ground-truth touch of the
//     recording measures the wall time from the arrival of the touch's last sample to the
//     final decision about it; and how often that decision agrees with the offline
//     pipeline (`tactile predict`'s) on the same touches. SECONDS: only the first SECONDS of
//     the recording (and the touches in them).
//
//   live_bench soak SKIN FACTOR MINUTES RECORD.h5 [BUFFER_SECONDS]
//     The headless workbench connected to sim://SKIN at FACTOR times its rate, recording
//     into RECORD.h5, drawing 60 frames a second for MINUTES; prints resident memory at the
//     start, every 10 minutes and at the end, with the buffer's own size.
#include <imgui.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "bench_support.h"
#include "live.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labels/predict.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/live/live_input.h"
#include "tactile/live/live_receiver.h"
#include "tactile/live/online_classifier.h"
#include "tactile/live/udp.h"
#include "workbench.h"

namespace {

using Clock = std::chrono::steady_clock;
using tactile::LiveSampleSource;
using tactile::bench::percentile;

double resident_mb() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / (1 << 20);
}

int ingest(double factor, double seconds) {
  const uint16_t port = tactile::UdpSocket::bind_to({"127.0.0.1", 0}).local_port();
  tactile::WorkbenchOptions options;
  options.connect = "udp://:" + std::to_string(port);
  options.skin = "nao";
  options.buffer_seconds = 60.0;
  options.settings_path = "/tmp/live_bench_settings.json";
  tactile::bench::PacedFrames frames(1400, 800);
  tactile::Workbench workbench(options);
  tactile::WorkbenchState& state = workbench.state();
  if (!state.error.empty()) {
    std::fprintf(stderr, "live_bench: %s\n", state.error.c_str());
    return 1;
  }
  // The sender: the simulator's datagrams, paced, onto the socket.
  std::atomic<bool> stop{false};
  std::atomic<int64_t> sent{0};
  std::atomic<double> newest_sent{-1.0};
  std::thread sender([&] {
    auto input = tactile::open_live_input(
        tactile::parse_live_address("sim://nao?rate=" + std::to_string(factor), "sender"));
    tactile::UdpSocket socket = tactile::UdpSocket::connect_to({"127.0.0.1", port});
    std::vector<uint8_t> datagram;
    const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(seconds));
    while (!stop && Clock::now() < end) {
      if (!input->next(datagram, 0.05)) continue;
      socket.send(datagram);
      ++sent;
      double time = 0.0;
      std::memcpy(&time, datagram.data() + 12, sizeof time);
      newest_sent = time;
    }
  });
  std::vector<double> behind_frames;
  for (int k = 0; k < 30; ++k) frames.draw(workbench);  // warm-up
  frames.ms.clear();
  const auto start = Clock::now();
  while (std::chrono::duration<double>(Clock::now() - start).count() < seconds + 1.0) {
    // How far the skin (drawn at the newest sample the frame took) is behind the newest
    // datagram sent when the frame began.
    const double sent_time = newest_sent.load();
    frames.draw(workbench);
    const auto& source = *state.document->source;
    if (source.sample_count() > 0 && sent_time >= 0.0) {
      const double lag = sent_time - source.time_of(source.sample_count() - 1);
      behind_frames.push_back(std::max(0.0, lag) / factor * 60.0);  // device s -> wall s -> frames
    }
  }
  stop = true;
  sender.join();
  for (int k = 0; k < 10; ++k) frames.draw(workbench);  // the last datagrams in flight
  const tactile::LiveCounters& counters = state.live.counters;
  std::printf(
      "{\"skin\": \"nao\", \"factor\": %.0f, \"samples_per_second\": %.0f, \"seconds\": %.0f,\n"
      " \"sent\": %lld, \"received\": %lld, \"lost\": %lld, \"broken\": %lld, "
      "\"dropped_at_handover\": %lld,\n"
      " \"frames\": %zu, \"frame_ms_median\": %.2f, \"frame_ms_p90\": %.2f, \"frame_ms_max\": "
      "%.2f,\n"
      " \"behind_frames_median\": %.2f, \"behind_frames_p99\": %.2f, \"behind_frames_max\": "
      "%.2f}\n",
      factor, 250.0 * factor, seconds, static_cast<long long>(sent.load()),
      static_cast<long long>(counters.datagrams), static_cast<long long>(counters.lost),
      static_cast<long long>(counters.broken), static_cast<long long>(counters.overflow),
      frames.ms.size(), percentile(frames.ms, 0.5), percentile(frames.ms, 0.9),
      percentile(frames.ms, 1.0), percentile(behind_frames, 0.5), percentile(behind_frames, 0.99),
      percentile(behind_frames, 1.0));
  return 0;
}

int latency(const std::string& model_path, const std::string& recording_path,
            const std::string& labels_path, double seconds) {
  const tactile::RecordingFile file(recording_path);
  const tactile::SkinLayout layout = tactile::load_layout(file.layout_id());
  tactile::LabelStore store(labels_path);
  tactile::LabelFilter filter;
  filter.recording = file.recording_id();
  filter.source = tactile::LabelSource::kGroundTruth;
  std::vector<tactile::Label> touches = store.list(filter);
  const double start_time = file.stream("skin").start_time;
  if (seconds > 0.0)  // only the touches of the part replayed
    std::erase_if(touches, [&](const tactile::Label& touch) {
      return touch.t1 > start_time + seconds - 1.0;
    });
  tactile::LiveReceiver receiver(
      tactile::open_live_input(tactile::parse_live_address(
          "replay://" + recording_path + "?seconds=" + std::to_string(seconds > 0 ? seconds : 1e9),
          "replay")),
      layout);
  LiveSampleSource source(
      receiver.source_info(),
      std::llround(receiver.source_info().rate_hz * ((seconds > 0 ? seconds : 600.0) + 10.0)));
  tactile::OnlineClassifier online(tactile::read_model_file(model_path), layout,
                                   receiver.source_info(),
                                   tactile::default_online_options(layout.id));
  // Wall time each touch's last sample arrived, and its final decision.
  std::vector<double> arrived(touches.size(), -1.0), decided(touches.size(), -1.0);
  std::vector<std::string> answer(touches.size());
  std::vector<double> compute_ms,
      end_shift_ms;  // of the final decisions: work, and segment end - touch end
  const auto start = Clock::now();
  const auto now = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  while (!receiver.ended() || receiver.ring().size() > 0) {
    receiver.ring().drain(
        [&](double time, std::span<const float> values) { source.add(time, values); });
    const double newest =
        source.sample_count() > 0 ? source.time_of(source.sample_count() - 1) : -1e300;
    for (size_t k = 0; k < touches.size(); ++k)
      if (arrived[k] < 0.0 && newest >= touches[k].t1) arrived[k] = now();
    online.update(source);
    for (const tactile::OnlineDecision& decision : online.take()) {
      if (!decision.final) continue;
      // The touch this decision is about: the one it overlaps most.
      size_t best = touches.size();
      double best_overlap = 0.0;
      for (size_t k = 0; k < touches.size(); ++k) {
        const double overlap =
            std::min(decision.t1, touches[k].t1) - std::max(decision.t0, touches[k].t0);
        if (overlap > best_overlap) best_overlap = overlap, best = k;
      }
      if (best < touches.size() && decided[best] < 0.0) {
        decided[best] = now();
        answer[best] = decision.class_name;
        compute_ms.push_back(1000.0 * decision.seconds);
        end_shift_ms.push_back(1000.0 * (decision.t1 - touches[best].t1));
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  online.wait_idle();
  // Offline: the same model on the same touches of the whole recording.
  const tactile::Recording recording = tactile::read_recording(recording_path);
  const tactile::Predictions offline =
      tactile::predict_segments(tactile::read_model_file(model_path), recording, layout, touches);
  std::map<std::pair<double, double>, std::string> offline_class;
  for (const tactile::Label& label : offline.labels)
    offline_class[{label.t0, label.t1}] = label.class_name;
  std::vector<double> latencies;
  int decided_count = 0, agreed = 0;
  for (size_t k = 0; k < touches.size(); ++k) {
    if (decided[k] < 0.0 || arrived[k] < 0.0) continue;
    ++decided_count;
    latencies.push_back(1000.0 * std::max(0.0, decided[k] - arrived[k]));
    const auto found = offline_class.find({touches[k].t0, touches[k].t1});
    if (found != offline_class.end() && found->second == answer[k]) ++agreed;
  }
  std::printf(
      "{\"skin\": \"%s\", \"rate_hz\": %.0f, \"touches\": %zu, \"decided\": %d, "
      "\"agree_with_offline\": %d,\n"
      " \"latency_ms_median\": %.0f, \"latency_ms_p90\": %.0f, \"latency_ms_max\": %.0f,\n"
      " \"classify_ms_median\": %.0f, \"segment_end_after_touch_end_ms_median\": %.0f, \"error\": "
      "\"%s\"}\n",
      layout.id.c_str(), receiver.source_info().rate_hz, touches.size(), decided_count, agreed,
      percentile(latencies, 0.5), percentile(latencies, 0.9), percentile(latencies, 1.0),
      percentile(compute_ms, 0.5), percentile(end_shift_ms, 0.5), online.error().c_str());
  return 0;
}

int soak(const std::string& skin, double factor, double minutes, const std::string& record,
         double buffer) {
  tactile::WorkbenchOptions options;
  options.connect = "sim://" + skin + "?rate=" + std::to_string(factor);
  options.record_path = record;
  options.buffer_seconds = buffer;
  options.settings_path = "/tmp/live_bench_settings.json";
  tactile::bench::PacedFrames frames(1400, 800);
  tactile::Workbench workbench(options);
  tactile::WorkbenchState& state = workbench.state();
  if (!state.error.empty()) {
    std::fprintf(stderr, "live_bench: %s\n", state.error.c_str());
    return 1;
  }
  const auto start = Clock::now();
  const auto elapsed_minutes = [&] {
    return std::chrono::duration<double>(Clock::now() - start).count() / 60.0;
  };
  const auto report = [&](const char* when) {
    const auto& source = static_cast<const LiveSampleSource&>(*state.document->source);
    const tactile::LiveCounters& counters = state.live.counters;
    std::printf(
        "{\"when\": \"%s\", \"minutes\": %.1f, \"device_hours\": %.2f, \"resident_mb\": %.1f, "
        "\"buffer_mb\": %.1f, \"recorded_samples\": %lld, \"received\": %lld, \"lost\": %lld, "
        "\"dropped_at_handover\": %lld, \"frame_ms_median\": %.2f, \"error\": \"%s\"}\n",
        when, elapsed_minutes(), source.duration() / 3600.0, resident_mb(),
        static_cast<double>(source.memory_bytes()) / (1 << 20),
        static_cast<long long>(state.live.recorded_samples),
        static_cast<long long>(counters.datagrams), static_cast<long long>(counters.lost),
        static_cast<long long>(counters.overflow), percentile(frames.ms, 0.5), state.error.c_str());
    std::fflush(stdout);
    frames.ms.clear();
  };
  for (int k = 0; k < 60; ++k) frames.draw(workbench);
  report("start");
  double next_report = 10.0;
  while (elapsed_minutes() < minutes) {
    frames.draw(workbench);
    if (elapsed_minutes() >= next_report) {
      report("every 10 minutes");
      next_report += 10.0;
    }
  }
  report("end");
  tactile::stop_recording(state, workbench.services().live);
  const tactile::RecordingFile file(record);
  std::printf("{\"recorded_file_samples\": %lld, \"cut_off\": %s}\n",
              static_cast<long long>(file.stream("skin").sample_count),
              file.cut_off() ? "true" : "false");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  try {
    if (mode == "ingest")
      return ingest(argc > 2 ? std::stod(argv[2]) : 10.0, argc > 3 ? std::stod(argv[3]) : 20.0);
    if (mode == "latency" && argc >= 5)
      return latency(argv[2], argv[3], argv[4], argc > 5 ? std::stod(argv[5]) : 0.0);
    if (mode == "soak" && argc >= 6)
      return soak(argv[2], std::stod(argv[3]), std::stod(argv[4]), argv[5],
                  argc > 6 ? std::stod(argv[6]) : 600.0);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "live_bench: %s\n", error.what());
    return 1;
  }
  std::fprintf(stderr,
               "usage: live_bench ingest [FACTOR] [SECONDS]\n"
               "       live_bench latency MODEL.json RECORDING.h5 LABELS.db [SECONDS]\n"
               "       live_bench soak SKIN FACTOR MINUTES RECORD.h5 [BUFFER_SECONDS]\n");
  return 2;
}
