// Simulated NAO Cellular Skin trials (paper 000, Kaboli et al., Sec 4; spec §1.1): one subject
// performs each of the nine touch classes `repetitions` times on the front and/or back of the
// robot, sitting still or moving; or, with multi-touch, the front/back pairs of Table 4 at once.

#include <algorithm>
#include <cmath>

#include "nao/nao_model.h"
#include "tactile/error.h"
#include "tactile/sim/sim_util.h"
#include "tactile/sim/simulator.h"

namespace tactile {

namespace {

using sim::nao::Gesture;
using sim::nao::SideArea;

constexpr int kNaoRepetitions = 3;  // the paper's training subjects: 3 per class

// Paper 000, Table 4: the multiple touch actions (front, back).
constexpr const char* kMultiTouchPairs[][2] = {
    {"poke", "poke"},  {"tickle", "tickle"}, {"push", "rub"},  {"slap", "push"},
    {"rub", "stroke"}, {"stroke", "stroke"}, {"punch", "pat"}, {"scratch", "punch"},
    {"pat", "punch"},  {"slap", "slap"}};

std::vector<SideArea> find_sides(const SkinLayout& layout) {
  std::vector<SideArea> sides;
  for (const char* id : {"front", "back"}) {
    const Group* group = layout.find_group(id);
    if (group == nullptr || group->taxels.empty())
      throw Error("layout " + layout.id,
                  std::string("the nao simulator needs a group \"") + id + "\"");
    SideArea side;
    side.id = id;
    side.low = {1e300, 1e300};
    side.high = {-1e300, -1e300};
    for (int64_t taxel_id : group->taxels) {
      const Taxel* taxel = layout.find_taxel(taxel_id);
      const int index = static_cast<int>(taxel - layout.taxels.data());
      side.cells.push_back(index);
      side.centres.push_back(taxel->position);
      side.centre.x += taxel->position.x / static_cast<double>(group->taxels.size());
      side.centre.y += taxel->position.y / static_cast<double>(group->taxels.size());
      for (const Point2& corner : taxel_outline(*taxel)) {
        side.low = {std::min(side.low.x, corner.x), std::min(side.low.y, corner.y)};
        side.high = {std::max(side.high.x, corner.x), std::max(side.high.y, corner.y)};
      }
    }
    side.pitch = 1e300;
    for (int a : side.cells)
      for (int b : side.cells)
        if (a != b)
          side.pitch = std::min(
              side.pitch, std::hypot(layout.taxels[a].position.x - layout.taxels[b].position.x,
                                     layout.taxels[a].position.y - layout.taxels[b].position.y));
    sides.push_back(std::move(side));
  }
  return sides;
}

int class_index(const SkinLayout& layout, const std::string& name) {
  const auto found = std::find(layout.classes.begin(), layout.classes.end(), name);
  if (found == layout.classes.end())
    throw Error("layout " + layout.id, "the multi-touch pairs need class \"" + name + "\"");
  return static_cast<int>(found - layout.classes.begin());
}

}  // namespace

SimulatedTrial simulate_nao_trial(const SkinLayout& layout, const SimulationOptions& options,
                                  int subject, int trial) {
  if (options.condition != "stationary" && options.condition != "moving")
    throw Error("--condition",
                "nao conditions are stationary and moving, not \"" + options.condition + "\"");
  if (!options.side.empty() && options.side != "front" && options.side != "back")
    throw Error("--side", "nao sides are front and back, not \"" + options.side + "\"");
  if (options.repetitions < 0) throw Error("--repetitions", "must not be negative");
  if (options.multi_touch && !options.side.empty())
    throw Error("--side", "multi-touch uses both sides at once; leave the side out");
  if (layout.classes.empty()) throw Error("layout " + layout.id, "has no classes to simulate");
  const double rate_hz = layout.sample_rate_hz > 0.0 ? layout.sample_rate_hz : 250.0;
  const int repetitions = options.repetitions > 0 ? options.repetitions : kNaoRepetitions;
  const std::vector<SideArea> sides = find_sides(layout);

  Random habit_random(derive_engine(options.seed, "nao-subject", subject));
  const sim::nao::SubjectHabits habits = sim::nao::draw_habits(habit_random);
  Random random(derive_engine(options.seed, "nao-trial", subject, trial));

  // Gestures one after another, separated by rests the subject chooses whatever the class.
  std::vector<Gesture> gestures;
  double cursor = random.uniform(1.0, 2.0);
  auto place = [&](const std::string& name, int index, int side, double start) {
    Gesture gesture = sim::nao::build_gesture(name, sides[side], habits, random, start, rate_hz);
    gesture.class_index = index;
    gesture.side = side;
    gestures.push_back(std::move(gesture));
    return static_cast<double>(gestures.back().last_sample()) / rate_hz;
  };
  if (options.multi_touch) {
    const int pair_count = static_cast<int>(std::size(kMultiTouchPairs));
    for (int pair : sim::shuffled_classes(pair_count, repetitions, random)) {
      // Two hands at once: the briefer action happens while the longer one lasts.
      const char* front = kMultiTouchPairs[pair][0];
      const char* back = kMultiTouchPairs[pair][1];
      place(front, class_index(layout, front), 0, cursor);
      place(back, class_index(layout, back), 1, cursor);
      Gesture& first = gestures[gestures.size() - 2];
      Gesture& second = gestures.back();
      const bool first_longer =
          first.contact_end - first.contact_start >= second.contact_end - second.contact_start;
      Gesture& longer = first_longer ? first : second;
      Gesture& shorter = first_longer ? second : first;
      const double slack = (longer.contact_end - longer.contact_start) -
                           (shorter.contact_end - shorter.contact_start);
      const double offset =
          longer.contact_start + random.uniform(0.0, 0.6) * slack - shorter.contact_start;
      const int64_t shift = std::llround(offset * rate_hz);
      sim::nao::shift_gesture(shift >= 0 ? shorter : longer, std::abs(shift), rate_hz);
      const double front_end = static_cast<double>(first.last_sample()) / rate_hz;
      const double back_end = static_cast<double>(second.last_sample()) / rate_hz;
      cursor = std::max(front_end, back_end) + random.uniform(1.0, 2.5);
    }
  } else {
    const int class_count = static_cast<int>(layout.classes.size());
    for (int index : sim::shuffled_classes(class_count, repetitions, random)) {
      const int side = options.side == "front"  ? 0
                       : options.side == "back" ? 1
                                                : static_cast<int>(random.integer(0, 1));
      cursor = place(layout.classes[index], index, side, cursor) + random.uniform(1.0, 2.5);
    }
  }
  const double duration = cursor + random.uniform(0.0, 0.5);
  const int64_t samples = static_cast<int64_t>(std::ceil(duration * rate_hz));

  // The paper trained on sitting down / standing up and tested walking on the front; multi-touch
  // was recorded sitting down and standing up (Sec 4.3, 4.4).
  std::string motion = "none";
  if (options.condition == "moving") {
    if (options.multi_touch || options.side == "back")
      motion = "sit-stand";
    else if (options.side == "front")
      motion = "walking";
    else
      motion = random.chance(0.5) ? "walking" : "sit-stand";
  }
  Random motion_random(derive_engine(options.seed, "nao-motion", subject, trial));
  const sim::nao::BodyMotion body =
      sim::nao::simulate_body_motion(motion, samples, rate_hz, motion_random);

  SimulatedTrial result;
  Recording& recording = result.recording;
  recording.id = simulated_recording_id("nao", subject, trial);
  recording.layout_id = layout.id;
  recording.metadata = sim::simulated_metadata("nao", subject, trial,
                                               options.multi_touch    ? "front+back"
                                               : options.side.empty() ? "both"
                                                                      : options.side,
                                               options.condition);
  recording.metadata["motion"] = motion;
  recording.metadata["scenario"] = options.multi_touch ? "multi-touch" : "single-touch";
  recording.metadata["repetitions"] = std::to_string(repetitions);
  recording.streams.push_back(sim::make_stream(layout, "skin", rate_hz, samples));
  // The skin's cells are the same hardware in every trial: their properties depend on the seed.
  Random hardware(derive_engine(options.seed, "nao-hardware"));
  Random noise(derive_engine(options.seed, "nao-noise", subject, trial));
  sim::nao::render_skin(layout, sides, gestures, body, rate_hz, hardware, noise,
                        recording.streams.back().samples);

  for (const Gesture& gesture : gestures) {
    result.labels.push_back(
        sim::ground_truth_label(recording.id, gesture.contact_start, gesture.contact_end,
                                layout.classes[gesture.class_index], sides[gesture.side].id));
  }
  std::stable_sort(result.labels.begin(), result.labels.end(),
                   [](const Label& a, const Label& b) { return a.t0 < b.t0; });
  return result;
}

}  // namespace tactile
