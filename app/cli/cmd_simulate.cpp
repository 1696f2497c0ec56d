// `tactile simulate`: synthetic recordings of any skin, or the demo workspace.
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "progress.h"
#include "tactile/error.h"
#include "tactile/skins/skin.h"
#include "tactile/skins/workspace.h"
#include "tactile/text.h"

namespace tactile::cli {

namespace {

struct SimulateArgs {
  std::string skin;
  std::string out;
  std::string demo;
  SimulationOptions options;
  bool json = false;
  bool video = false;  // a simulated camera beside each recording
  ShardArgs shard;
};

void print_summary(const SimulationSummary& summary, const std::string& folder, bool json,
                   bool demo) {
  if (json) {
    nlohmann::json out = {{"folder", folder},
                          {"files", summary.files},
                          {"labels", summary.labels},
                          {"seconds_recorded", summary.seconds_recorded}};
    std::cout << out.dump(2) << "\n";
  } else {
    std::cout << "wrote " << summary.files.size() << " recordings (" << summary.seconds_recorded
              << " s) and " << summary.labels << " labels to " << folder << "\n";
    // The demo is made to be looked at: say how.
    if (demo) std::cout << "open it: tactile-workbench " << folder << "\n";
  }
}

void run_simulate(const SimulateArgs& args) {
  if (args.demo.empty() == args.out.empty())
    throw Error("simulate", "give either --demo DIR or --skin ID --out DIR");
  if (!args.out.empty() && args.skin.empty()) throw Error("--skin", "required with --out");
  if (!args.demo.empty() && !args.skin.empty()) throw Error("--skin", "not used with --demo");
  if (args.options.side != "" && args.options.side != "front" && args.options.side != "back")
    throw Error("--side", "must be front or back, not '" + args.options.side + "'");
  if (args.options.condition != "stationary" && args.options.condition != "moving")
    throw Error("--condition",
                "must be stationary or moving, not '" + args.options.condition + "'");
  if (!args.demo.empty() && !args.shard.shard.empty())
    throw Error("--shard", "the demo workspace does not shard: give --skin ID --out DIR");
  if (args.video && !args.shard.shard.empty())
    throw Error("--video", "not with --shard: film the merged folder's recordings");
  const ShardPlan plan =
      shard_plan(args.shard, (std::filesystem::path(args.out) / "simulate").string());
  ProgressBar bar(args.demo.empty() ? "simulate " + args.skin : "demo workspace");
  auto progress = [&](int done, int total) { bar.update(done, total); };
  if (plan.shard.active()) {  // its recordings only: the labels are merge's to store
    const SimulatedTrials trials =
        simulate_trials(args.out, args.skin, args.options, plan.shard, progress);
    bar.finish();
    write_shard_part(plan, simulation_part(trials, args.out, args.skin, args.options, plan.shard));
    return;
  }
  const SimulationSummary summary =
      args.demo.empty() ? write_simulation(args.out, args.skin, args.options, progress)
                        : write_demo_workspace(args.demo, args.options.seed, progress);
  bar.finish();
  if (args.video) {
    ProgressBar filming("filming");
    const std::vector<std::string> videos =
        write_camera_videos(summary.files, args.options.seed,
                            [&](int done, int total) { filming.update(done, total); });
    filming.finish();
    if (!args.json)
      std::cout << "wrote " << videos.size() << " camera videos, attached as \"camera\"\n";
  }
  print_summary(summary, args.demo.empty() ? args.out : args.demo, args.json, !args.demo.empty());
}

}  // namespace

void merge_simulate(const std::vector<Part>& parts, const std::string& out) {
  const SimulationSummary summary = merge_simulation_parts(parts, out);
  print_summary(summary, out, false, false);
}

void register_simulate(CLI::App& app) {
  auto args = std::make_shared<SimulateArgs>();
  CLI::App* command =
      app.add_subcommand("simulate", "Write synthetic recordings with ground-truth labels");
  command->add_option("--skin", args->skin,
                      "Skin to simulate: " + joined(simulated_skin_ids()) +
                          ", or grid:RxC (a large uncalibrated pressure grid, 7 gestures)");
  command->add_option("--out", args->out, "Output folder (recordings as .h5, labels in labels.db)");
  command->add_option("--demo", args->demo,
                      "Write the small demo workspace of all five skins to this folder");
  command->add_option("--subjects", args->options.subjects, "Number of subjects")
      ->capture_default_str();
  command->add_option("--trials", args->options.trials, "Trials per subject")
      ->capture_default_str();
  command
      ->add_option("--repetitions", args->options.repetitions,
                   "Gestures per class per trial (0: the skin's default)")
      ->capture_default_str();
  command->add_option("--seed", args->options.seed, "Random seed; same seed, same bytes")
      ->capture_default_str();
  command->add_option("--condition", args->options.condition, "nao: stationary or moving")
      ->capture_default_str();
  command->add_flag("--multi-touch", args->options.multi_touch,
                    "nao: a front and a back gesture at once");
  command->add_option("--side", args->options.side, "nao: touch only the front or the back");
  command
      ->add_option("--faults", args->options.faults,
                   "Sensor faults over each trial: none, realistic, or stuck=N,dead=N,drift=S,"
                   "crosstalk=S,offsets=S,rest=P,rest_level=S,rest_patch=S,rest_gap=SECONDS "
                   "(docs/SIMULATION.md)")
      ->capture_default_str();
  command->add_flag("--json", args->json, "Print a machine-readable summary");
  command->add_flag("--video", args->video,
                    "Film each recording with a simulated camera (a hand reaching each touch) and "
                    "attach the video as \"camera\" (docs/VIDEO.md)");
  add_shard_options(command, args->shard);
  command->callback([args] { run_simulate(*args); });
}

}  // namespace tactile::cli
