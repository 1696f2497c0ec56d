// The NAO pipeline on one simulated trial: the proximity segmenter finds every ground-truth
// touch, every extractor gives a finite row for each, and the features differ between classes
// the way Kaboli et al. describe the gestures (a slap is brief, a push long; a palm covers more
// of the skin than a fingertip poke).
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "tactile/features/kaboli.h"
#include "tactile/features/koo.h"
#include "tactile/features/naya.h"
#include "tactile/features/silvera_tawil.h"
#include "tactile/segment/proximity.h"
#include "tactile/sim/simulator.h"
#include "tactile/skins/skin.h"

namespace tactile {
namespace {

struct Trial {
  SkinLayout layout = load_layout("nao");
  SimulatedTrial simulated = skin_record("nao").simulate(layout, SimulationOptions{}, 0, 0);
};

const Trial& trial() {
  static const Trial shared;
  return shared;
}

// Mean of one feature column per class over the ground-truth labels; every row finite.
std::map<std::string, double> class_means(const FeatureExtractor& extractor, size_t column) {
  const Trial& data = trial();
  const Recording prepared = extractor.preprocess(data.simulated.recording, data.layout);
  std::map<std::string, double> sums;
  std::map<std::string, int> counts;
  for (const Label& label : data.simulated.labels) {
    const FeatureResult result = extractor.extract({prepared, data.layout, label});
    EXPECT_TRUE(result.skip_reason.empty())
        << extractor.name() << " " << label.class_name << ": " << result.skip_reason;
    if (!result.skip_reason.empty()) continue;
    EXPECT_EQ(result.values.size(), extractor.columns(data.layout).size());
    for (double value : result.values) EXPECT_TRUE(std::isfinite(value)) << extractor.name();
    sums[label.class_name] += result.values[column];
    counts[label.class_name] += 1;
  }
  for (auto& [name, sum] : sums) sum /= counts[name];
  return sums;
}

TEST(NaoSimulatedTrial, ProximitySegmenterFindsEveryTouchOnItsBodyPart) {
  const Trial& data = trial();
  const std::vector<Label> found = segment_proximity(data.simulated.recording, data.layout, {});
  ASSERT_FALSE(data.simulated.labels.empty());
  for (const Label& truth : data.simulated.labels) {
    int overlapping = 0;
    for (const Label& label : found)
      if (label.region == truth.region && label.t0 < truth.t1 && truth.t0 < label.t1) ++overlapping;
    EXPECT_EQ(overlapping, 1) << truth.class_name << " at " << truth.t0 << " s on " << truth.region;
  }
}

TEST(NaoSimulatedTrial, SlapIsBrieferThanPushAndPalmsCoverMoreThanAPoke) {
  const auto contact_time = class_means(*make_silvera_tawil_extractor({}), 3);
  EXPECT_LT(contact_time.at("slap") * 5.0, contact_time.at("push"));
  const auto area = class_means(*make_naya_extractor({}), 1);
  EXPECT_GT(area.at("slap"), 3.0 * area.at("poke"));
  EXPECT_GT(area.at("push"), 3.0 * area.at("poke"));
  // Koo's contact-area changes: rubbing keeps making and breaking contact, a push holds it.
  const auto changes = class_means(*make_koo_extractor({}), 2);
  EXPECT_GT(changes.at("rub"), changes.at("push"));
  // Kaboli's force Activity: a punch loads the cells hardest.
  const auto force_activity = class_means(*make_kaboli_extractor({}), 15);
  for (const auto& [name, value] : force_activity)
    if (name != "punch") {
      EXPECT_GT(force_activity.at("punch"), value) << name;
    }
}

}  // namespace
}  // namespace tactile
