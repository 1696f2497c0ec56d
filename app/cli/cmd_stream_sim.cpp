// `tactile stream-sim --skin ID --to udp://HOST:PORT [--rate-factor X] [--duration S]
//  [--seed S]`: what the skin's device would send, from the simulator, as live UDP packets
// (docs/PACKETS.md), paced at the device's rate times X.
#include <algorithm>
#include <cmath>
#include <future>
#include <iomanip>
#include <iostream>
#include <memory>
#include <random>
#include <sstream>

#include "commands.h"
#include "tactile/error.h"
#include "tactile/live/packet_stream.h"
#include "tactile/live/udp.h"
#include "tactile/sim/simulator.h"
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

// The stream a simulated trial puts on the wire, moved to start at `device_time`.
Stream trial_stream(SimulatedTrial trial, double device_time) {
  std::vector<Stream>& streams = trial.recording.streams;
  auto skin = std::find_if(streams.begin(), streams.end(),
                           [](const Stream& stream) { return stream.name == "skin"; });
  if (skin == streams.end() && streams.size() == 1) skin = streams.begin();
  if (skin == streams.end())
    throw Error("simulator " + trial.recording.id, "no stream named \"skin\"");
  Stream stream = std::move(*skin);
  const double shift = device_time - stream.time_of(0);
  stream.start_time += shift;
  for (double& time : stream.timestamps) time += shift;
  return stream;
}

void run_stream_sim(const StreamSimOptions& options) {
  const UdpEndpoint destination = parse_udp_url(options.to, "--to");
  if (!(options.rate_factor > 0.0) || !std::isfinite(options.rate_factor))
    throw Error("--rate-factor", "must be a number above 0");
  if (!(options.duration >= 0.0) || !std::isfinite(options.duration))
    throw Error("--duration", "must be a number of seconds, 0 or more (0: one trial)");
  const PacketFormatInfo format = packet_format_info(options.skin);
  const SkinLayout layout = load_layout(options.skin);
  const TrialGenerator& generator = skin_record(options.skin, "--skin").simulate;
  SimulationOptions simulation;
  simulation.seed = options.seed;
  simulation.subjects = 1;
  const auto simulate = [&](int trial) {
    return std::async(std::launch::async, [&generator, &layout, simulation, trial] {
      return generator(layout, simulation, 0, trial);
    });
  };

  if (!(options.loss >= 0.0 && options.loss < 1.0))
    throw Error("--loss", "must be a fraction in [0, 1)");
  UdpSocket socket = UdpSocket::connect_to(destination);
  std::mt19937_64 dice(options.seed ^ 0x5EED10550ULL);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int64_t dropped = 0;
  PacedSender sender(
      [&](std::span<const uint8_t> datagram) {
        if (options.loss > 0.0 && unit(dice) < options.loss) {
          ++dropped;  // lost on the way: counted as sent
          return true;
        }
        return socket.send(datagram);
      },
      options.rate_factor);
  uint32_t sequence = 0;
  double device_time = 0.0;
  int64_t remaining =
      options.duration > 0.0
          ? static_cast<int64_t>(std::llround(options.duration * format.sample_rate_hz))
          : -1;  // known once the first trial is simulated
  if (remaining == 0)
    throw Error("--duration", "is shorter than one sample of the " + options.skin + " device (" +
                                  std::to_string(1.0 / format.sample_rate_hz) + " s)");
  int trials = 0;
  // The next trial is simulated while this one is sent, so a long trial never stalls the wire.
  std::future<SimulatedTrial> next = simulate(0);
  while (remaining != 0) {
    const Stream stream = trial_stream(next.get(), device_time);
    ++trials;
    if (remaining < 0) remaining = stream.sample_count();
    const int64_t count = std::min(remaining, stream.sample_count());
    if (count == 0)
      throw Error("simulator " + options.skin,
                  "trial " + std::to_string(trials) + " has no samples");
    if (remaining > count) next = simulate(trials);
    const PacketEncoder encoder(layout, stream);
    sender.send(encoder, stream, 0, count, sequence);
    remaining -= count;
    device_time += static_cast<double>(count) / format.sample_rate_hz;
  }

  const SendTotals& totals = sender.totals();
  const double seconds = sender.elapsed_seconds();
  // The first datagram leaves at 0 s, so N datagrams span N - 1 intervals.
  const double rate = seconds > 0.0 ? static_cast<double>(totals.datagrams - 1) / seconds : 0.0;
  std::ostringstream out;
  out << std::fixed << std::setprecision(3);
  out << "stream-sim: " << options.skin << " to " << destination.url() << "\n"
      << "datagrams: " << totals.datagrams << "\n"
      << "bytes: " << totals.bytes << "\n"
      << "samples: " << totals.samples << " (" << trials << (trials == 1 ? " trial" : " trials")
      << ", " << device_time << " s of device time)\n"
      << "seconds: " << seconds << "\n"
      << std::setprecision(1) << "rate: " << rate << " datagrams/s (device "
      << format.datagrams_per_second() << " x " << options.rate_factor << " = "
      << format.datagrams_per_second() * options.rate_factor << ")\n";
  if (dropped > 0) out << "dropped: " << dropped << " (--loss)\n";
  if (totals.refused > 0)
    out << "refused: " << totals.refused << " (nobody was listening at " << destination.url()
        << ")\n";
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
  command->add_option("--loss", options->loss,
                      "Fraction of datagrams to drop at random, as a lossy network would (default 0)");
  command->callback([options] { run_stream_sim(*options); });
}

}  // namespace tactile::cli
