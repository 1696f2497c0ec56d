#include "tactile/sim/simulator.h"

#include <map>

#include "tactile/error.h"

namespace tactile {

// Generators register here; each skin's file defines its own.
SimulatedTrial simulate_nao_trial(const SkinLayout&, const SimulationOptions&, int subject,
                                  int trial);
SimulatedTrial simulate_tsa_trial(const SkinLayout&, const SimulationOptions&, int subject,
                                  int trial);
SimulatedTrial simulate_fur_trial(const SkinLayout&, const SimulationOptions&, int subject,
                                  int trial);
SimulatedTrial simulate_robovie_trial(const SkinLayout&, const SimulationOptions&, int subject,
                                      int trial);
SimulatedTrial simulate_flux_trial(const SkinLayout&, const SimulationOptions&, int subject,
                                   int trial);

namespace {

const std::map<std::string, TrialGenerator>& generators() {
  static const std::map<std::string, TrialGenerator> table = {{"nao", simulate_nao_trial},
                                                              {"tsa", simulate_tsa_trial},
                                                              {"fur", simulate_fur_trial},
                                                              {"robovie", simulate_robovie_trial},
                                                              {"flux", simulate_flux_trial}};
  return table;
}

}  // namespace

std::vector<std::string> simulated_skins() { return {"nao", "tsa", "fur", "robovie", "flux"}; }

const TrialGenerator& trial_generator(const std::string& skin) {
  const auto found = generators().find(skin);
  if (found == generators().end())
    throw Error("--skin " + skin, "no simulator for this skin (have nao, tsa, fur, robovie, flux)");
  return found->second;
}

}  // namespace tactile
