#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <set>

#include "tactile/error.h"
#include "tactile/sim/robovie_sim.h"
#include "tactile/stats/statistics.h"

namespace tactile {
namespace {

using sim::robovie::Films;

const SkinLayout& robovie_layout() {
  static const SkinLayout layout = load_layout("robovie");
  return layout;
}

// Trials are costly enough to share between tests: seed 1, trial 0 of subjects 0..5.
const SimulatedTrial& cached_trial(int subject) {
  static std::map<int, SimulatedTrial> trials;
  auto found = trials.find(subject);
  if (found == trials.end()) {
    SimulationOptions options;
    options.seed = 1;
    found = trials.emplace(subject, simulate_robovie_trial(robovie_layout(), options, subject, 0))
                .first;
  }
  return found->second;
}
constexpr int kSubjects = 6;

const Stream& skin_of(const SimulatedTrial& trial) {
  const Stream* skin = trial.recording.find_stream("skin");
  EXPECT_NE(skin, nullptr);
  return *skin;
}

const Label& stage_label(const SimulatedTrial& trial, const std::string& stage) {
  for (const Label& label : trial.labels)
    if (label.class_name == stage) return label;
  ADD_FAILURE() << "no label " << stage;
  return trial.labels.front();
}

// Mean over the films of each body part of the films' RMS (counts) about their own mean,
// over [t0 + skip, t1): how strongly each part's signals moved in a stage.
std::map<std::string, double> part_rms(const Stream& skin, double t0, double t1,
                                       double skip = 0.0) {
  const Films films = sim::robovie::films_of(robovie_layout());
  const int64_t first = skin.index_at(t0 + skip);
  const int64_t last = std::min(skin.index_at(t1), skin.sample_count());
  std::map<std::string, std::pair<double, int>> sums;
  for (int64_t film = 0; film < films.count(); ++film) {
    const Eigen::ArrayXd x = skin.samples.col(film).segment(first, last - first).cast<double>();
    const double rms = std::sqrt((x - x.mean()).square().mean());
    auto& slot = sums[films.body_parts[films.body_part[film]]];
    slot.first += rms;
    ++slot.second;
  }
  std::map<std::string, double> result;
  for (const auto& [part, sum] : sums) result[part] = sum.first / sum.second;
  return result;
}

std::string loudest(const std::map<std::string, double>& rms) {
  return std::max_element(rms.begin(), rms.end(),
                          [](const auto& a, const auto& b) { return a.second < b.second; })
      ->first;
}

//---- Determinism and shape of a trial

TEST(SimRobovie, SameSeedSubjectAndTrialGiveIdenticalBytes) {
  SimulationOptions options;
  options.seed = 7;
  const SimulatedTrial a = simulate_robovie_trial(robovie_layout(), options, 2, 1);
  const SimulatedTrial b = simulate_robovie_trial(robovie_layout(), options, 2, 1);
  const Stream& skin_a = skin_of(a);
  const Stream& skin_b = skin_of(b);
  ASSERT_EQ(skin_a.samples.size(), skin_b.samples.size());
  EXPECT_EQ(std::memcmp(skin_a.samples.data(), skin_b.samples.data(),
                        sizeof(float) * skin_a.samples.size()),
            0);
  EXPECT_EQ(a.recording.find_stream("commands")->timestamps,
            b.recording.find_stream("commands")->timestamps);
  ASSERT_EQ(a.labels.size(), b.labels.size());
  for (size_t k = 0; k < a.labels.size(); ++k) {
    EXPECT_EQ(a.labels[k].t0, b.labels[k].t0);
    EXPECT_EQ(a.labels[k].t1, b.labels[k].t1);
    EXPECT_EQ(a.labels[k].region, b.labels[k].region);
  }

  options.seed = 8;
  const SimulatedTrial c = simulate_robovie_trial(robovie_layout(), options, 2, 1);
  const Stream& skin_c = skin_of(c);
  EXPECT_TRUE(skin_c.samples.rows() != skin_a.samples.rows() ||
              std::memcmp(skin_a.samples.data(), skin_c.samples.data(),
                          sizeof(float) * skin_a.samples.size()) != 0);
  EXPECT_NE(c.recording.find_stream("commands")->timestamps,
            a.recording.find_stream("commands")->timestamps);
}

TEST(SimRobovie, RecordingCarriesTheSkinAndItsIdentity) {
  const SimulatedTrial& trial = cached_trial(1);
  EXPECT_EQ(trial.recording.id, "robovie-s02-t01");
  EXPECT_EQ(trial.recording.layout_id, "robovie");
  EXPECT_EQ(trial.recording.metadata.at("subject"), "s02");
  const Stream& skin = skin_of(trial);
  EXPECT_EQ(skin.rate_hz, 100.0);
  EXPECT_EQ(skin.channel_count(), 274);
  EXPECT_EQ(skin.channels.front(), "s001");
  // A Table I session lasts minutes, not seconds.
  EXPECT_GT(skin.duration(), 90.0);
  EXPECT_LT(skin.duration(), 400.0);
}

TEST(SimRobovie, EverySampleIsAFiniteSigned16BitCount) {
  for (int subject = 0; subject < 3; ++subject) {
    const SampleMatrix& samples = skin_of(cached_trial(subject)).samples;
    ASSERT_TRUE(samples.allFinite());
    EXPECT_GE(samples.minCoeff(), -32768.0f);
    EXPECT_LE(samples.maxCoeff(), 32767.0f);
    EXPECT_TRUE((samples.array() == samples.array().round()).all()) << "ADC counts are integers";
  }
}

TEST(SimRobovie, CommandsStreamHasFifteenIncreasingTimeStamps) {
  const SimulatedTrial& trial = cached_trial(0);
  const Stream* commands = trial.recording.find_stream("commands");
  ASSERT_NE(commands, nullptr);
  ASSERT_EQ(commands->channels, std::vector<std::string>{"stage"});
  ASSERT_EQ(commands->sample_count(), 15);
  ASSERT_EQ(commands->timestamps.size(), 15u);
  const double end = skin_of(trial).duration();
  EXPECT_GT(commands->timestamps.front(), 0.0);
  for (int k = 0; k < 15; ++k) {
    EXPECT_EQ(commands->samples(k, 0), static_cast<float>(k));
    if (k > 0) {
      EXPECT_GT(commands->timestamps[k], commands->timestamps[k - 1] + 1.0);
    }
    EXPECT_LT(commands->timestamps[k], end);
  }
}

TEST(SimRobovie, OneGroundTruthLabelPerStageFromItsCommandToTheNext) {
  const SimulatedTrial& trial = cached_trial(3);
  const std::vector<double>& commands = trial.recording.find_stream("commands")->timestamps;
  const double end = skin_of(trial).duration();
  ASSERT_EQ(trial.labels.size(), robovie_layout().classes.size());
  for (size_t k = 0; k < trial.labels.size(); ++k) {
    const Label& label = trial.labels[k];
    EXPECT_EQ(label.class_name, robovie_layout().classes[k]);
    EXPECT_EQ(label.recording, trial.recording.id);
    EXPECT_EQ(label.source, LabelSource::kGroundTruth);
    EXPECT_EQ(label.annotator, "simulator");
    EXPECT_EQ(label.confidence, 1.0);
    EXPECT_DOUBLE_EQ(label.t0, commands[k]);
    EXPECT_DOUBLE_EQ(label.t1, k + 1 < commands.size() ? commands[k + 1] : end);
    EXPECT_GE(label.t0, 0.0);
    EXPECT_LE(label.t1, end);
    EXPECT_TRUE(label.region == "all" || robovie_layout().find_group(label.region) != nullptr)
        << label.region;
  }
}

TEST(SimRobovie, ThreeTrialsStartFromTheThreePositionsOfThePaper) {
  std::set<std::string> approaches;
  SimulationOptions options;
  for (int trial = 0; trial < 3; ++trial)
    approaches.insert(simulate_robovie_trial(robovie_layout(), options, 4, trial)
                          .recording.metadata.at("approach"));
  EXPECT_EQ(approaches, (std::set<std::string>{"front", "right", "left"}));
}

TEST(SimRobovie, LayoutWithoutPiezoFilmsIsRejected) {
  EXPECT_THROW(simulate_robovie_trial(make_grid_layout(4, 4), SimulationOptions{}, 0, 0), Error);
  EXPECT_THROW(simulate_robovie_trial(robovie_layout(), SimulationOptions{}, -1, 0), Error);
}

//---- The piezo film

TEST(SimRobovie, ConstantPressDecaysToZeroWithinASecond) {
  const Films films = sim::robovie::films_of(robovie_layout());
  const sim::robovie::Robot robot = sim::robovie::make_robot(films, 3);
  const int64_t samples = 600;
  SampleMatrix load = SampleMatrix::Zero(samples, films.count());
  // A palm pressing 10 N on the crown from 1 s to 5 s, rising in 0.1 s.
  sim::robovie::Contact press;
  press.onset = 1.0;
  press.duration = 4.0;
  press.rise = 0.1;
  press.fall = 0.1;
  press.force = 10.0;
  press.center = sim::robovie::body_area(films, "head", sim::robovie::View::kBack).center();
  sim::robovie::add_contact_load(films, press, 100.0, load);
  const Eigen::MatrixXf still = Eigen::MatrixXf::Zero(samples, sim::robovie::kJointCount);
  Random noise(derive_engine(3, "test-noise"));
  sim::robovie::piezo_output(robot, still, 100.0, noise, load);

  // The film that answered most, measured on the output.
  Eigen::Index film = 0;
  load.middleRows(100, 50).cwiseAbs().colwise().maxCoeff().maxCoeff(&film);
  const Eigen::ArrayXd x = load.col(film).cast<double>();
  const Eigen::ArrayXd rest = x.segment(0, 100);
  const double baseline = rest.mean();
  const double noise_rms = std::sqrt((rest - baseline).square().mean());
  const double onset_peak = (x.segment(100, 30) - baseline).maxCoeff();
  EXPECT_GT(onset_peak, 50.0 * noise_rms) << "pressing gives a strong positive swing";
  // Still pressing, 1 s after the rise: back to the baseline within the noise.
  const Eigen::ArrayXd held = x.segment(210, 280) - baseline;
  EXPECT_LT(std::abs(held.mean()), noise_rms);
  EXPECT_LT(held.abs().maxCoeff(), 5.0 * noise_rms);
  // Letting go answers with the opposite sign.
  EXPECT_LT((x.segment(490, 30) - baseline).minCoeff(), -0.5 * onset_peak);
}

TEST(SimRobovie, TheRubberCarriesAPressToTheFilmsAroundItFallingWithDistance) {
  // One newton on one film of the front: every film of the front carries 0.5 exp(-d / 40 mm)
  // of it, the back nothing, the film itself all of it.
  const Films films = sim::robovie::films_of(robovie_layout());
  Eigen::Index pressed = 0;
  while (films.view[pressed] != sim::robovie::View::kFront) ++pressed;
  SampleMatrix load = SampleMatrix::Zero(2, films.count());
  load(1, pressed) = 1.0f;
  sim::robovie::spread_through_skin(films, load);
  EXPECT_FLOAT_EQ(load(1, pressed), 1.0f);
  EXPECT_EQ(load.row(0).cwiseAbs().maxCoeff(), 0.0f) << "a sample without load stays without";
  int nearer = 0;
  for (Eigen::Index film = 0; film < films.count(); ++film) {
    if (film == pressed) continue;
    if (films.view[film] != sim::robovie::View::kFront) {
      EXPECT_EQ(load(1, film), 0.0f) << "film " << film << " lies on the back";
      continue;
    }
    const double gap = std::hypot(films.center[film].x - films.center[pressed].x,
                                  films.center[film].y - films.center[pressed].y);
    EXPECT_NEAR(load(1, film), 0.5 * std::exp(-gap / 40.0), 1e-6) << "film " << film;
    nearer += gap < 60.0;
  }
  EXPECT_GT(nearer, 0) << "the pressed film has neighbours within 60 mm";
}

TEST(SimRobovie, FilmsCarryNoDirectCurrentOverATrial) {
  // A high-pass output integrates to the load's net change, zero over a whole session.
  const SampleMatrix& samples = skin_of(cached_trial(2)).samples;
  const Eigen::ArrayXf means = samples.colwise().mean().transpose().array();
  EXPECT_LT(means.abs().maxCoeff(), 40.0f);
}

//---- What the stages look like on the skin

TEST(SimRobovie, HandShakeExcitesTheRightHandMost) {
  for (int subject = 0; subject < kSubjects; ++subject) {
    const SimulatedTrial& trial = cached_trial(subject);
    const Label& label = stage_label(trial, "Let's shake hands.");
    const auto rms = part_rms(skin_of(trial), label.t0, label.t1);
    EXPECT_EQ(loudest(rms), "hand-right") << "subject " << subject;
    EXPECT_GT(rms.at("hand-right"), 3.0 * rms.at("hand-left")) << "subject " << subject;
    EXPECT_EQ(label.region, "hand-right");
  }
}

TEST(SimRobovie, HugExcitesTheBackAndTheSides) {
  const std::set<std::string> hugged = {"back-upper", "back-lower", "side-right", "side-left"};
  for (int subject = 0; subject < kSubjects; ++subject) {
    const SimulatedTrial& trial = cached_trial(subject);
    const Label& label = stage_label(trial, "Give me a hug.");
    const auto rms = part_rms(skin_of(trial), label.t0, label.t1);
    EXPECT_TRUE(hugged.count(loudest(rms))) << "subject " << subject << ": " << loudest(rms);
    for (const char* far : {"head", "face", "thigh-right", "thigh-left", "hand-right"})
      EXPECT_GT(rms.at("back-upper") + rms.at("back-lower"), 2.0 * rms.at(far)) << far;
    EXPECT_TRUE(hugged.count(label.region)) << label.region;
  }
}

TEST(SimRobovie, TicklingExcitesTheSides) {
  for (int subject = 0; subject < kSubjects; ++subject) {
    const SimulatedTrial& trial = cached_trial(subject);
    const Label& label = stage_label(trial, "Tickle me.");
    const auto rms = part_rms(skin_of(trial), label.t0, label.t1);
    const std::string top = loudest(rms);
    EXPECT_TRUE(top == "side-right" || top == "side-left") << "subject " << subject << ": " << top;
  }
}

TEST(SimRobovie, PatOnTheHeadExcitesTheHead) {
  for (int subject = 0; subject < kSubjects; ++subject) {
    const SimulatedTrial& trial = cached_trial(subject);
    const Label& label = stage_label(trial, "I wish you'd pat me on the head");
    EXPECT_EQ(loudest(part_rms(skin_of(trial), label.t0, label.t1)), "head") << subject;
  }
}

TEST(SimRobovie, UntouchedStagesShowOnlyTheRobotsMotion) {
  int untouched = 0;
  double arms = 0.0, torso = 0.0;
  for (int subject = 0; subject < kSubjects; ++subject) {
    const SimulatedTrial& trial = cached_trial(subject);
    const Stream& skin = skin_of(trial);
    double touched_peak = 0.0;
    for (const Label& label : trial.labels) {
      // Skip the first 1.5 s: a release just before the command still rings for a moment.
      const int64_t first = skin.index_at(label.t0 + 1.5);
      const int64_t last = std::min(skin.index_at(label.t1), skin.sample_count());
      if (last - first < 200) continue;
      const SampleMatrix window = skin.samples.middleRows(first, last - first);
      const Eigen::RowVectorXf centre = window.colwise().mean();
      const float peak = (window.rowwise() - centre).cwiseAbs().maxCoeff();
      if (label.region != "all") {
        touched_peak = std::max<double>(touched_peak, peak);
        continue;
      }
      ++untouched;
      EXPECT_LT(peak, 1500.0f) << label.class_name << ", subject " << subject;
      const auto rms = part_rms(skin, label.t0, label.t1, 1.5);
      for (const char* part :
           {"shoulder-right", "shoulder-left", "upper-arm-right", "upper-arm-left"})
        arms += rms.at(part);
      for (const char* part : {"chest-lower", "back-lower", "hip-right", "hip-left"})
        torso += rms.at(part);
    }
    EXPECT_GT(touched_peak, 1500.0) << "subject " << subject;
  }
  EXPECT_GE(untouched, kSubjects) << "most sessions have stages where nobody touches";
  // The robot's gestures shake the arms' and shoulders' films more than the torso's.
  EXPECT_GT(arms, 1.5 * torso);
}

TEST(SimRobovie, TheRobotPlaysEachStagesOwnMovementInEveryTrial) {
  // "Whee!" and "Let's play!" move both arms the same way every time; lines that only talk
  // come with a small gesture now and then. In the second after the command, before anyone
  // answers with a touch, the arms' films show it.
  std::map<std::string, std::vector<double>> arms;
  for (int subject = 0; subject < kSubjects; ++subject) {
    const SimulatedTrial& trial = cached_trial(subject);
    const Stream& skin = skin_of(trial);
    for (const char* stage :
         {"Whee!", "Let's play!", "What's your name?", "Thanks", "Nice to meet you."}) {
      const Label& label = stage_label(trial, stage);
      const auto rms = part_rms(skin, label.t0, label.t0 + 1.1);
      const double sum = rms.at("upper-arm-right") + rms.at("upper-arm-left") +
                         rms.at("shoulder-right") + rms.at("shoulder-left");
      const bool talking = std::string(stage) != "Whee!" && std::string(stage) != "Let's play!";
      arms[talking ? "talking" : stage].push_back(sum);
    }
  }
  for (const char* stage : {"Whee!", "Let's play!"}) {
    const double typical = stats::median(arms[stage]);
    for (const double value : arms[stage]) EXPECT_NEAR(value, typical, 0.25 * typical) << stage;
    EXPECT_GT(typical, 2.0 * stats::median(arms["talking"])) << stage;
  }
}

}  // namespace
}  // namespace tactile
