// `tactile stream-listen --skin ID --from udp://HOST:PORT --duration S [--idle S]
//  [--datagrams N] [--bound-to FILE] [--out FILE.h5] [--json]`: receives live packets
//  (docs/PACKETS.md) for S seconds (or until
// the stream has been silent for --idle seconds), decodes and checks them, reports loss,
// restarts, stalls, clock jumps and rate, and optionally writes what arrived as a recording
// (on the stream's clock: a sender's restart or clock jump does not move it; docs/LIVE.md).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "commands.h"
#include "tactile/error.h"
#include "tactile/io/atomic_file.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/live/packet_stream.h"
#include "tactile/live/udp.h"
#include "tactile/skins/skin.h"
#include "tactile/text.h"

namespace tactile::cli {

namespace {

struct StreamListenOptions {
  std::string skin;
  std::string from;
  double duration = 0.0;
  double idle = 0.0;      // 0: listen for the whole duration
  int64_t datagrams = 0;  // stop once this many have arrived; 0: no such limit
  std::string bound_to;   // where to say the port listened on (port 0: the system's choice)
  std::string out;
  bool json = false;
};

void run_stream_listen(const StreamListenOptions& options) {
  const UdpEndpoint local = parse_udp_url(options.from, "--from", UdpUse::kListen);
  if (!(options.duration > 0.0) || !std::isfinite(options.duration))
    throw Error("--duration", "must be a number of seconds above 0");
  if (!(options.idle >= 0.0) || !std::isfinite(options.idle))
    throw Error("--idle", "must be a number of seconds, 0 or more (0: never)");
  if (options.datagrams < 0) throw Error("--datagrams", "must be 0 (no limit) or more");
  skin_record(options.skin, "--skin " + options.skin);  // an unknown skin is named at its option
  packet_format_info(options.skin);                     // refuses a skin without a packet format
  PacketCollector collector(load_layout(options.skin), !options.out.empty());
  UdpSocket socket = UdpSocket::bind_to(local);
  // The address listened on, with the port the system gave when port 0 was asked for. Said once
  // the socket listens, so a sender started after the file appears loses nothing.
  const std::string listening = UdpEndpoint{local.host, socket.local_port()}.url();
  if (!options.bound_to.empty()) write_file_atomically(options.bound_to, listening + "\n");

  using Clock = std::chrono::steady_clock;
  const Clock::time_point end = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                   std::chrono::duration<double>(options.duration));
  const Clock::time_point start = Clock::now();
  Clock::time_point first_arrival, last_arrival;
  int64_t oversized = 0;
  // Larger than any datagram UDP can carry, so a size above it cannot happen unnoticed.
  std::vector<uint8_t> buffer(65536);
  for (;;) {
    const Clock::time_point now = Clock::now();
    double left = std::chrono::duration<double>(end - now).count();
    const bool streaming = collector.datagrams() > 0 || oversized > 0;
    if (streaming && options.idle > 0.0)
      left =
          std::min(left, options.idle - std::chrono::duration<double>(now - last_arrival).count());
    if (left <= 0.0) break;
    // A silence is counted as a stall when the stream resumes after it (the one that ends
    // --idle is the end, not a stall).
    const std::optional<size_t> size = socket.receive(buffer, left);
    if (!size) continue;  // the loop head decides whether time is up
    last_arrival = Clock::now();
    if (collector.datagrams() == 0 && oversized == 0) first_arrival = last_arrival;
    if (*size > buffer.size()) {
      ++oversized;
      continue;
    }
    collector.add(std::span<const uint8_t>(buffer.data(), *size),
                  std::chrono::duration<double>(last_arrival - start).count());
    if (options.datagrams > 0 && collector.datagrams() >= options.datagrams) break;
  }

  const SequenceTracker& sequence = collector.sequence();
  const double seconds = std::chrono::duration<double>(last_arrival - first_arrival).count();
  // N datagrams arriving over `seconds` span N - 1 intervals.
  const double rate = seconds > 0.0 ? static_cast<double>(sequence.received() - 1) / seconds : 0.0;
  const LiveTimeline& timeline = collector.timeline();
  if (options.json) {
    nlohmann::json report = {{"skin", options.skin},
                             {"from", local.url()},
                             {"datagrams", sequence.received()},
                             {"bytes", collector.bytes()},
                             {"samples", collector.samples()},
                             {"first_time", collector.first_time()},
                             {"end_time", collector.end_time()},
                             {"lost", sequence.lost()},
                             {"duplicated", sequence.duplicated()},
                             {"reordered", sequence.reordered()},
                             {"broken", collector.broken() + oversized},
                             {"saturated", collector.saturated()},
                             {"restarts", sequence.restarts()},
                             {"stalls", timeline.stalls()},
                             {"clock_jumps", timeline.clock_jumps()},
                             {"late_dropped", timeline.late_dropped()},
                             {"seconds", seconds},
                             {"rate", rate}};
    std::cout << report.dump(2) << "\n";
  } else {
    std::ostringstream out;
    out << std::fixed << std::setprecision(3);
    out << "stream-listen: " << options.skin << " on " << listening << "\n"
        << "datagrams: " << sequence.received() << "\n"
        << "bytes: " << collector.bytes() << "\n"
        << "samples: " << collector.samples() << " (stream time " << collector.first_time()
        << " to " << collector.end_time() << " s)\n"
        << "lost: " << sequence.lost() << "\n"
        << "duplicated: " << sequence.duplicated() << "\n"
        << "reordered: " << sequence.reordered() << "\n"
        << "broken: " << collector.broken() + oversized << "\n"
        << "saturated: " << collector.saturated() << "\n"
        << "restarts: " << sequence.restarts() << "\n"
        << "stalls: " << timeline.stalls() << "\n"
        << "clock jumps: " << timeline.clock_jumps() << "\n"
        << "seconds: " << seconds << "\n"
        << std::setprecision(1) << "rate: " << rate << " datagrams/s\n";
    std::cout << out.str();
  }
  if (collector.broken() > 0)
    std::cerr << "tactile: " << collector.broken()
              << " broken datagrams, the last: " << collector.last_error() << "\n";
  if (oversized > 0) std::cerr << "tactile: " << oversized << " datagrams over 64 KiB\n";

  if (!options.out.empty()) {
    const std::string id = std::filesystem::path(options.out).stem().string();
    if (collector.samples() == 0)
      throw Error(options.out, "nothing was received on " + local.url() + ", nothing written");
    Recording recording = collector.recording(id);
    recording.metadata["source"] = local.url();
    write_recording(options.out, recording);
    if (!options.json) std::cout << "written: " << options.out << "\n";
  }
}

}  // namespace

void register_stream_listen(CLI::App& app) {
  auto options = std::make_shared<StreamListenOptions>();
  CLI::App* command = app.add_subcommand(
      "stream-listen", "Receive live UDP packets of a skin, report loss and rate, record them");
  command->add_option("--skin", options->skin, "Skin: " + joined(packet_skin_ids()))->required();
  command
      ->add_option("--from", options->from,
                   "Where to listen, udp://HOST:PORT (port 0: any free port, see --bound-to)")
      ->required();
  command->add_option("--duration", options->duration, "Seconds to listen at most")->required();
  command->add_option("--idle", options->idle,
                      "Stop once no datagram has come for this many seconds (default: never)");
  command->add_option("--datagrams", options->datagrams,
                      "Stop once this many datagrams have arrived (default: no such limit)");
  command->add_option("--bound-to", options->bound_to,
                      "Once listening, write the address listened on (udp://HOST:PORT) to this "
                      "file: with port 0 in --from, the free port the system gave");
  command->add_option("--out", options->out, "Write what arrived as a recording (.h5)");
  command->add_flag("--json", options->json, "Print the report as JSON");
  command->callback([options] { run_stream_listen(*options); });
}

}  // namespace tactile::cli
