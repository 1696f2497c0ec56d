// Kaboli et al. (spec §1.2-1.8): zero-mean, dynamic cell selection, the per-cell and per-area
// 16-value descriptors (test vector K4) and the `kaboli` extractor on hand-built recordings.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <utility>

#include "kaboli_k4_data.h"
#include "nao_test_recording.h"
#include "tactile/dsp/zero_mean.h"
#include "tactile/error.h"
#include "tactile/features/kaboli.h"
#include "tactile/segment/nao_window.h"

namespace tactile {
namespace {

using testing::k4_cells;
using testing::k4_recording;
using testing::K4Recording;
using testing::segment;
using Vector = std::vector<double>;

//---- Test vector K4

KaboliDescriptor k4_cell_descriptor(const testing::K4Cell& cell,
                                    NcorrMode mode = NcorrMode::kRanks) {
  std::vector<std::span<const double>> forces(cell.force.begin(), cell.force.end());
  return kaboli_cell_descriptor(cell.ax, cell.ay, cell.az, forces, mode);
}

void expect_descriptor(std::span<const double> actual, const Vector& expected) {
  ASSERT_EQ(actual.size(), expected.size());
  for (size_t k = 0; k < expected.size(); ++k)
    EXPECT_NEAR(actual[k], expected[k], 1e-5 * std::max(1.0, std::abs(expected[k])))
        << "value " << k;
}

const Vector kK4Cell1 = {0.0622573, -0.609994, 0,      0.12501,  -0.562544, 0,
                         0.671875,  1.44771,   1.0175, 0.375,    0.808122,  1.44368,
                         0.25,      1.27775,   1.225,  0.0618229};
const Vector kK4Cell2 = {-0.666667, 0,    0,       -0.662589, 0,    0,       2.25,     0.989743,
                         2.04167,   0.25, 1.97949, 1.02083,   0.25, 1.51186, 0.824958, 0.0399479};
const Vector kK4BodyPart = {-0.20147, -0.203331, 0,        -0.179193, -0.187515, 0,
                            0.973958, 0.812485,  1.01972,  0.208333,  0.929203,  0.821503,
                            0.166667, 0.92987,   0.683319, 0.0339236};
const Vector kK4Contact = {-0.302205, -0.304997, 0,       -0.26879, -0.281272, 0,
                           1.46094,   1.21873,   1.52959, 0.3125,   1.3938,    1.23225,
                           0.25,      1.39481,   1.02498, 0.0508854};

TEST(KaboliCellDescriptor, MatchesVectorK4ForBothContactedCells) {
  expect_descriptor(k4_cell_descriptor(k4_cells()[0]), kK4Cell1);
  expect_descriptor(k4_cell_descriptor(k4_cells()[1]), kK4Cell2);
}

TEST(KaboliCellDescriptor, IsUnchangedByZeroMeanPreprocessing) {
  const testing::K4Cell& raw = k4_cells()[0];
  const auto shifted = [](const Vector& x) {
    const Eigen::VectorXd centred =
        zero_mean(Eigen::Map<const Eigen::VectorXd>(x.data(), x.size()));
    return Vector(centred.data(), centred.data() + centred.size());
  };
  testing::K4Cell centred{shifted(raw.ax), shifted(raw.ay), shifted(raw.az), {}};
  for (const Vector& force : raw.force) centred.force.push_back(shifted(force));
  EXPECT_NEAR(Eigen::Map<const Eigen::VectorXd>(centred.az.data(), 8).mean(), 0.0, 1e-15);
  EXPECT_DOUBLE_EQ(centred.az[0], -0.5);
  expect_descriptor(k4_cell_descriptor(centred), kK4Cell1);
}

TEST(KaboliCellDescriptor, Eq6ModeUsesTheRankDifferenceFormula) {
  // Cell 1's ax has ties (0 three times, -1 twice): eq. 6 differs from Pearson of ranks there.
  const KaboliDescriptor ranks = k4_cell_descriptor(k4_cells()[0], NcorrMode::kRanks);
  const KaboliDescriptor eq6 = k4_cell_descriptor(k4_cells()[0], NcorrMode::kEq6);
  EXPECT_NEAR(ranks[3], 0.12501, 1e-5);
  EXPECT_GT(std::abs(eq6[3] - ranks[3]), 1e-3);
  EXPECT_EQ(eq6[0], ranks[0]);  // Pearson and Hjorth values do not depend on the mode
  EXPECT_EQ(eq6[7], ranks[7]);
}

TEST(KaboliAreaDescriptor, MatchesVectorK4InBothNormalisations) {
  const std::vector<KaboliDescriptor> contacted = {k4_cell_descriptor(k4_cells()[0]),
                                                   k4_cell_descriptor(k4_cells()[1])};
  expect_descriptor(kaboli_area_descriptor(contacted, 3, AreaNormalisation::kBodyPart),
                    kK4BodyPart);
  expect_descriptor(kaboli_area_descriptor(contacted, 3, AreaNormalisation::kContact), kK4Contact);
}

TEST(KaboliAreaDescriptor, NoContactedCellGivesTheZeroVector) {
  const KaboliDescriptor none = kaboli_area_descriptor({}, 3, AreaNormalisation::kBodyPart);
  expect_descriptor(none, Vector(16, 0.0));
  expect_descriptor(kaboli_area_descriptor({}, 3, AreaNormalisation::kContact), Vector(16, 0.0));
}

TEST(DynamicCellSelection, ContactIsStrictlyCloserThanFiftyMillimetres) {
  const std::vector<float> cell1 = {200, 20, 30, 200}, cell2 = {60, 45, 200, 200},
                           cell3 = {50, 50, 50, 50};
  EXPECT_TRUE(cell_in_contact(cell1, 50.0));
  EXPECT_TRUE(cell_in_contact(cell2, 50.0));
  EXPECT_FALSE(cell_in_contact(cell3, 50.0));
  EXPECT_FALSE(cell_in_contact(std::vector<float>{NAN, 200.0f}, 50.0));
  EXPECT_FALSE(cell_in_contact(cell2, 45.0));
}

TEST(ZeroMean, RemovesTheMeanOfEachSignal) {
  const Eigen::VectorXd x = (Eigen::VectorXd(4) << 1, 2, 3, 6).finished();
  const Eigen::VectorXd centred = zero_mean(x);
  EXPECT_DOUBLE_EQ(centred[0], -2.0);
  EXPECT_DOUBLE_EQ(centred[3], 3.0);
  EXPECT_EQ(zero_mean(Eigen::VectorXd()).size(), 0);
  Eigen::MatrixXd signals(3, 2);
  signals << 1, 10, 2, 10, 6, 40;
  zero_mean_columns(signals);
  EXPECT_DOUBLE_EQ(signals(0, 0), -2.0);
  EXPECT_DOUBLE_EQ(signals(2, 1), 20.0);
  EXPECT_DOUBLE_EQ(signals(1, 1), -10.0);
}

//---- The extractor on a hand-built NAO recording

FeatureResult extract(const FeatureExtractor& extractor, const K4Recording& k4,
                      const Label& label) {
  return extractor.extract({k4.recording, k4.layout, label});
}

// The paper as printed: no high-pass on the accelerometers (vector K4 is computed without it).
Parameters as_printed() {
  Parameters parameters;
  parameters.set("motion_hz", "0");
  return parameters;
}

TEST(KaboliExtractor, GivesVectorK4ForTheTouchedBodyPart) {
  const K4Recording k4 = k4_recording();
  const auto extractor = make_kaboli_extractor(as_printed());
  EXPECT_EQ(extractor->name(), "kaboli");
  ASSERT_EQ(extractor->columns(k4.layout).size(), 16u);
  EXPECT_EQ(extractor->columns(k4.layout)[7].name, "mobility_ax");
  EXPECT_EQ(extractor->columns(k4.layout)[15].name, "force_activity");
  const FeatureResult result = extract(*extractor, k4, segment(0.0, 8 / 250.0, "front"));
  ASSERT_TRUE(result.skip_reason.empty()) << result.skip_reason;
  expect_descriptor(result.values, kK4BodyPart);
}

TEST(KaboliExtractor, ContactNormalisationDividesByTheContactedCells) {
  const K4Recording k4 = k4_recording();
  Parameters parameters = as_printed();
  parameters.set("norm_mode", "contact");
  const FeatureResult result =
      extract(*make_kaboli_extractor(parameters), k4, segment(0.0, 8 / 250.0, "front"));
  ASSERT_TRUE(result.skip_reason.empty()) << result.skip_reason;
  expect_descriptor(result.values, kK4Contact);
}

TEST(KaboliExtractor, RegionAllChoosesTheSideWithMoreContactedCells) {
  K4Recording k4 = k4_recording();
  // One back cell touched, with signals unlike the front's: the front (two cells) must win.
  testing::set_signal(k4.recording, k4.layout, 20, "prox", {10, 10, 10, 10, 10, 10, 10, 10});
  testing::set_signal(k4.recording, k4.layout, 20, "ax", {0, 3, 0, 3, 0, 3, 0, 3});
  const auto extractor = make_kaboli_extractor(as_printed());
  expect_descriptor(extract(*extractor, k4, segment(0.0, 8 / 250.0, "all")).values, kK4BodyPart);
  const FeatureResult back = extract(*extractor, k4, segment(0.0, 8 / 250.0, "back"));
  ASSERT_TRUE(back.skip_reason.empty()) << back.skip_reason;
  EXPECT_NEAR(back.values[6], 2.25 / 16.0, 1e-6);  // Act(ax) = 2.25 over N_c = 16 back cells
  // Three more back cells in contact (with flat signals): now the back has more.
  for (int64_t cell : {21, 22, 23})
    testing::set_range(k4.recording, k4.layout, cell, "prox", 0, 8, 30.0f);
  const FeatureResult all = extract(*extractor, k4, segment(0.0, 8 / 250.0, "all"));
  EXPECT_NEAR(all.values[6], 2.25 / 16.0, 1e-6);
}

// A robot sitting down while a hand strokes one of its cells: the torso leans 0.5 rad over
// 2.5 s, which turns gravity through the cell's z axis by about half a g. The stroke shakes
// the cell at 40 Hz with 0.02 g. The descriptor must see the stroke, not the robot.
TEST(KaboliExtractor, TheRobotsOwnMotionLeavesTheAccelerometerDescriptorsAlone) {
  const SkinLayout layout = load_layout("nao");
  const int64_t samples = 1500;  // 6 s
  auto touched = [&](bool sitting_down) {
    Recording recording = testing::nao_recording(layout, samples);
    std::vector<double> ax(samples), ay(samples), az(samples), force(samples);
    for (int64_t s = 0; s < samples; ++s) {
      const double t = static_cast<double>(s) / testing::kNaoRate;
      const bool stroking = t >= 2.0 && t < 4.0;
      const double shake = stroking ? 0.02 * std::sin(2.0 * std::numbers::pi * 40.0 * t) : 0.0;
      const double lean = sitting_down && t >= 1.5 && t < 4.0
                              ? 0.5 * std::pow(std::sin(std::numbers::pi * (t - 1.5) / 2.5), 2)
                              : 0.0;
      ax[s] = 0.5 * shake;
      ay[s] = -std::cos(lean) - 0.3 * shake;
      az[s] = std::sin(lean) + shake;
      force[s] = stroking ? 0.3 + 0.1 * std::sin(2.0 * std::numbers::pi * 2.0 * t) : 0.0;
    }
    for (const auto& [modality, values] :
         {std::pair{"ax", ax}, {"ay", ay}, {"az", az}, {"f1", force}})
      testing::set_signal(recording, layout, 3, modality, values);
    testing::set_range(recording, layout, 3, "prox", 500, 1000, 5.0f);
    return recording;
  };
  const Recording still = touched(false), moving = touched(true);
  const Label stroke = segment(1.9, 4.1, "front");
  auto descriptor = [&](const Recording& recording, const Parameters& parameters) {
    const FeatureResult result =
        make_kaboli_extractor(parameters)->extract({recording, layout, stroke});
    EXPECT_TRUE(result.skip_reason.empty()) << result.skip_reason;
    return result.values;
  };
  const Vector filtered_still = descriptor(still, {}), filtered_moving = descriptor(moving, {});
  // Activity of az (index 12) and the correlations (0-5) are the stroke's, motion or not.
  EXPECT_NEAR(filtered_moving[12] / filtered_still[12], 1.0, 0.05);
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(filtered_moving[k], filtered_still[k], 0.05) << k;
  // As printed (no high-pass), the lean swamps the stroke's az activity a hundred times over.
  const Vector raw_still = descriptor(still, as_printed()),
               raw_moving = descriptor(moving, as_printed());
  EXPECT_GT(raw_moving[12], 100.0 * raw_still[12]);
  // Force is not filtered: the same either way.
  EXPECT_NEAR(filtered_moving[15], raw_moving[15], 1e-12);
}

TEST(KaboliExtractor, SkipsWhenNoCellIsInContact) {
  const K4Recording k4 = k4_recording();
  // Samples 8-19 are at rest: every proximity reads 200 mm.
  const FeatureResult result =
      extract(*make_kaboli_extractor({}), k4, segment(10 / 250.0, 19 / 250.0, "front"));
  EXPECT_EQ(result.skip_reason, "no cell in contact");
  EXPECT_TRUE(result.values.empty());
  // The contact distance is a parameter: at 10 mm nothing in K4 is close enough.
  Parameters strict;
  strict.set("threshold_mm", "10");
  EXPECT_EQ(
      extract(*make_kaboli_extractor(strict), k4, segment(0.0, 8 / 250.0, "front")).skip_reason,
      "no cell in contact");
}

TEST(KaboliExtractor, SkipsSegmentsTooShortForComplexity) {
  const K4Recording k4 = k4_recording();
  const FeatureResult result =
      extract(*make_kaboli_extractor({}), k4, segment(1 / 250.0, 3 / 250.0, "front"));
  EXPECT_NE(result.skip_reason.find("2 samples"), std::string::npos) << result.skip_reason;
  EXPECT_FALSE(
      extract(*make_kaboli_extractor({}), k4, segment(5.0, 6.0, "front")).skip_reason.empty());
}

TEST(KaboliExtractor, NonFiniteSampleInAContactedCellNamesItsChannel) {
  K4Recording k4 = k4_recording();
  k4.recording.streams[0].samples(4, testing::nao_column(k4.layout, 2, "ay")) = NAN;
  const FeatureResult result =
      extract(*make_kaboli_extractor({}), k4, segment(0.0, 8 / 250.0, "front"));
  EXPECT_NE(result.skip_reason.find("c02.ay"), std::string::npos) << result.skip_reason;
  EXPECT_NE(result.skip_reason.find("0.016"), std::string::npos) << result.skip_reason;
  // A NaN in a cell not in contact is never read.
  K4Recording other = k4_recording();
  other.recording.streams[0].samples(4, testing::nao_column(other.layout, 3, "ay")) = NAN;
  EXPECT_TRUE(extract(*make_kaboli_extractor({}), other, segment(0.0, 8 / 250.0, "front"))
                  .skip_reason.empty());
}

TEST(KaboliExtractor, UnknownRegionIsSkippedWithItsName) {
  const K4Recording k4 = k4_recording();
  const FeatureResult result =
      extract(*make_kaboli_extractor({}), k4, segment(0.0, 8 / 250.0, "head"));
  EXPECT_NE(result.skip_reason.find("\"head\""), std::string::npos) << result.skip_reason;
}

TEST(KaboliExtractor, ConstantSignalsGiveFiniteZeros) {
  K4Recording k4 = k4_recording();
  // Cell 1 in contact throughout, but every signal constant.
  auto& samples = k4.recording.streams[0].samples;
  for (const char* modality : {"ax", "ay", "az", "f1", "f2", "f3"})
    samples.col(testing::nao_column(k4.layout, 1, modality)).setConstant(0.7f);
  for (const char* modality : {"prox"})
    samples.col(testing::nao_column(k4.layout, 1, modality)).setConstant(5.0f);
  const FeatureResult result =
      extract(*make_kaboli_extractor({}), k4, segment(12 / 250.0, 20 / 250.0, "front"));
  ASSERT_TRUE(result.skip_reason.empty()) << result.skip_reason;
  expect_descriptor(result.values, Vector(16, 0.0));
}

TEST(KaboliExtractor, BadParametersNameTheKey) {
  Parameters bad_mode;
  bad_mode.set("norm_mode", "AVERAGE");
  try {
    make_kaboli_extractor(bad_mode);
    FAIL();
  } catch (const Error& error) {
    EXPECT_NE(error.message().find("norm_mode"), std::string::npos);
    EXPECT_NE(error.message().find("BODY_PART"), std::string::npos);
  }
  Parameters negative;
  negative.set("threshold_mm", "-5");
  EXPECT_THROW(make_kaboli_extractor(negative), Error);
  Parameters typo;
  typo.set("ncorr", "EQ6");
  EXPECT_THROW(make_kaboli_extractor(typo), Error);
  Parameters motion;
  motion.set("motion_hz", "-1");
  EXPECT_THROW(make_kaboli_extractor(motion), Error);
  Parameters order;
  order.set("motion_order", "3");
  try {
    make_kaboli_extractor(order);
    FAIL();
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("motion_order"), std::string::npos) << error.what();
  }
}

TEST(KaboliExtractor, AWalkingRobotsGaitLeavesAQuietPushAlone) {
  // A push barely shakes the cell (a 30 Hz tremor of 0.005 g); a walking NAO bobs 0.06 g at
  // its 2 Hz step. The default high-pass (4th order, 7 Hz) keeps the push's activity; a
  // 2nd-order one at 5 Hz lets the gait through at several times the push's own.
  const SkinLayout layout = load_layout("nao");
  const int64_t samples = 1500;  // 6 s
  auto pushed = [&](bool walking) {
    Recording recording = testing::nao_recording(layout, samples);
    std::vector<double> ax(samples), ay(samples), az(samples), force(samples);
    for (int64_t s = 0; s < samples; ++s) {
      const double t = static_cast<double>(s) / testing::kNaoRate;
      const double tremor =
          t >= 2.0 && t < 4.0 ? 0.005 * std::sin(2.0 * std::numbers::pi * 30.0 * t) : 0.0;
      const double gait = walking ? 0.06 * std::sin(2.0 * std::numbers::pi * 2.0 * t) : 0.0;
      ax[s] = 0.3 * tremor;
      ay[s] = -1.0 + gait + 0.5 * tremor;
      az[s] = tremor;
      force[s] = t >= 2.0 && t < 4.0 ? 1.0 : 0.0;
    }
    for (const auto& [modality, values] :
         {std::pair{"ax", ax}, {"ay", ay}, {"az", az}, {"f1", force}})
      testing::set_signal(recording, layout, 3, modality, values);
    testing::set_range(recording, layout, 3, "prox", 500, 1000, 5.0f);
    return recording;
  };
  const Recording still = pushed(false), walking = pushed(true);
  const Label push = segment(1.9, 4.1, "front");
  auto activity_ay = [&](const Recording& recording, const Parameters& parameters) {
    const FeatureResult result =
        make_kaboli_extractor(parameters)->extract({recording, layout, push});
    EXPECT_TRUE(result.skip_reason.empty()) << result.skip_reason;
    return result.values[9];
  };
  EXPECT_NEAR(activity_ay(walking, {}) / activity_ay(still, {}), 1.0, 0.05);
  Parameters second_order;
  second_order.set("motion_hz", "5");
  second_order.set("motion_order", "2");
  EXPECT_GT(activity_ay(walking, second_order), 3.0 * activity_ay(still, second_order));
}

TEST(KaboliExtractor, RecordingWithoutTheSkinChannelsIsAnError) {
  K4Recording k4 = k4_recording();
  k4.recording.streams[0].channels[0] = "renamed";  // c01.ax
  try {
    extract(*make_kaboli_extractor({}), k4, segment(0.0, 8 / 250.0, "front"));
    FAIL();
  } catch (const Error& error) {
    EXPECT_NE(error.message().find("c01.ax"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace tactile
