// `tactile stream-sim --skin ID --to udp://HOST:PORT [--rate-factor X] [--duration S]
//  [--seed S]`: what the skin's device would send, from the simulator, as live UDP packets
// (docs/PACKETS.md), paced at the device's rate times X: exactly what `sim://SKIN` delivers to
// the workbench (live/live_input.h), sent on.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <random>
#include <sstream>

#include "commands.h"
#include "tactile/error.h"
#include "tactile/live/live_input.h"
#include "tactile/live/packets.h"
#include "tactile/live/udp.h"
#include "tactile/skins/skin.h"
#include "tactile/text.h"

namespace tactile::cli {

namespace {

struct StreamSimOptions {
  std::string skin;
  std::string to;
  double rate_factor = 1.0;
  double duration = 0.0;  // 0: one simulated trial
  uint64_t seed = 1;
  double loss = 0.0;  // fraction of datagrams not sent (a lossy network, for testing receivers)
};

void run_stream_sim(const StreamSimOptions& options) {
  const UdpEndpoint destination = parse_udp_url(options.to, "--to", UdpUse::kSend);
  if (!(options.rate_factor > 0.0) || !std::isfinite(options.rate_factor))
    throw Error("--rate-factor", "must be a number above 0");
  if (!(options.duration >= 0.0) || !std::isfinite(options.duration))
    throw Error("--duration", "must be a number of seconds, 0 or more (0: one trial)");
  if (!(options.loss >= 0.0 && options.loss < 1.0))
    throw Error("--loss", "must be a fraction in [0, 1)");
  skin_record(options.skin, "--skin " + options.skin);  // an unknown skin is named at its option
  const PacketFormatInfo format = packet_format_info(options.skin);
  if (options.duration > 0.0 && std::llround(options.duration * format.sample_rate_hz) == 0)
    throw Error("--duration", "is shorter than one sample of the " + options.skin + " device (" +
                                  std::to_string(1.0 / format.sample_rate_hz) + " s)");
  // What the workbench's `sim://SKIN` delivers, paced by the same input: one trial, or trials
  // until the duration is reached.
  std::unique_ptr<DatagramInput> input = open_live_input(parse_live_address(
      "sim://" + options.skin + "?seed=" + std::to_string(options.seed) + "&rate=" +
          shortest_text(options.rate_factor) + (options.duration > 0.0 ? "" : "&trials=1"),
      "--skin"));

  UdpSocket socket = UdpSocket::connect_to(destination);
  std::mt19937_64 dice(options.seed ^ 0x5EED10550ULL);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int64_t datagrams = 0, bytes = 0, samples = 0, dropped = 0, refused = 0;
  double device_time = 0.0;
  std::chrono::steady_clock::time_point first_sent, last_sent;
  std::vector<uint8_t> datagram;
  while (!input->ended()) {
    if (!input->next(datagram, 1.0)) continue;
    const PacketHeader header = decode_packet_header(datagram);
    // Device time starts at 0: the datagram that starts at the duration is the first not sent.
    if (options.duration > 0.0 && header.time >= options.duration - 0.5 / format.sample_rate_hz)
      break;
    last_sent = std::chrono::steady_clock::now();
    if (datagrams == 0) first_sent = last_sent;
    ++datagrams;
    bytes += static_cast<int64_t>(datagram.size());
    samples += header.sample_count;
    device_time = header.time + header.sample_count / format.sample_rate_hz;
    if (options.loss > 0.0 && unit(dice) < options.loss)
      ++dropped;  // lost on the way: counted as sent
    else if (!socket.send(datagram))
      ++refused;
  }

  const double seconds = std::chrono::duration<double>(last_sent - first_sent).count();
  // The first datagram leaves at 0 s, so N datagrams span N - 1 intervals.
  const double rate = seconds > 0.0 ? static_cast<double>(datagrams - 1) / seconds : 0.0;
  std::ostringstream out;
  out << std::fixed << std::setprecision(3);
  out << "stream-sim: " << options.skin << " to " << destination.url() << "\n"
      << "datagrams: " << datagrams << "\n"
      << "bytes: " << bytes << "\n"
      << "samples: " << samples << " (" << device_time << " s of device time)\n"
      << "seconds: " << seconds << "\n"
      << std::setprecision(1) << "rate: " << rate << " datagrams/s (device "
      << format.datagrams_per_second() << " x " << options.rate_factor << " = "
      << format.datagrams_per_second() * options.rate_factor << ")\n";
  if (dropped > 0) out << "dropped: " << dropped << " (--loss)\n";
  if (refused > 0)
    out << "refused: " << refused << " (nobody was listening at " << destination.url() << ")\n";
  std::cout << out.str();
}

}  // namespace

void register_stream_sim(CLI::App& app) {
  auto options = std::make_shared<StreamSimOptions>();
  CLI::App* command = app.add_subcommand(
      "stream-sim", "Send a simulated skin's signals as live UDP packets (docs/PACKETS.md)");
  command->add_option("--skin", options->skin, "Skin: " + joined(simulated_skin_ids()))->required();
  command->add_option("--to", options->to, "Destination, udp://HOST:PORT")->required();
  command->add_option("--rate-factor", options->rate_factor,
                      "Send at the device's rate times this (default 1)");
  command->add_option("--duration", options->duration,
                      "Seconds of device time to send; trials loop (default: one trial)");
  command->add_option("--seed", options->seed, "Simulator seed (default 1)");
  command->add_option(
      "--loss", options->loss,
      "Fraction of datagrams to drop at random, as a lossy network would (default 0)");
  command->callback([options] { run_stream_sim(*options); });
}

}  // namespace tactile::cli
