// The baselines Kaboli et al. adapted (spec §1.10-1.13): Naya (K5), Silvera-Tawil (K6) and Koo
// (K7) as pure functions and as extractors on the hand-built K4 recording.
#include <gtest/gtest.h>

#include <cmath>

#include "kaboli_k4_data.h"
#include "tactile/dsp/rest_offset.h"
#include "tactile/error.h"
#include "tactile/features/koo.h"
#include "tactile/features/naya.h"
#include "tactile/features/silvera_tawil.h"
#include "tactile/segment/nao_window.h"

namespace tactile {
namespace {

using testing::k4_cells;
using testing::k4_recording;
using testing::K4Recording;
using testing::segment;
using Vector = std::vector<double>;

constexpr double kK4ForceThreshold = 0.15;

// K5's 9 force elements: cell 1 sensors 1-3, cell 2 sensors 1-3, cell 3 sensors 1-3.
Eigen::MatrixXd k4_force() {
  Eigen::MatrixXd force(8, 9);
  for (int cell = 0; cell < 3; ++cell)
    for (int sensor = 0; sensor < 3; ++sensor)
      for (int t = 0; t < 8; ++t)
        force(t, 3 * cell + sensor) =
            k4_cells()[static_cast<size_t>(cell)].force[static_cast<size_t>(sensor)][t];
  return force;
}

template <size_t N>
void expect_values(const std::array<double, N>& actual, const Vector& expected) {
  ASSERT_EQ(N, expected.size());
  for (size_t k = 0; k < N; ++k)
    EXPECT_NEAR(actual[k], expected[k], 1e-5 * std::max(1.0, std::abs(expected[k])))
        << "value " << k;
}

void expect_values(const std::vector<double>& actual, const Vector& expected) {
  ASSERT_EQ(actual.size(), expected.size());
  for (size_t k = 0; k < expected.size(); ++k)
    EXPECT_NEAR(actual[k], expected[k], 1e-5 * std::max(1.0, std::abs(expected[k])))
        << "value " << k;
}

//---- Contact flags and contact time (§1.10)

TEST(ForceContact, BinarisesAtTheThresholdInclusiveAndCountsContactSamples) {
  const Eigen::ArrayXXd contact = contact_elements(k4_force(), kK4ForceThreshold);
  const Eigen::VectorXd area = contact.rowwise().sum().matrix();
  const Vector expected_area = {0, 1, 3, 5, 5, 3, 0, 0};
  for (int t = 0; t < 8; ++t)
    EXPECT_EQ(area[t], expected_area[static_cast<size_t>(t)]) << "t " << t;
  EXPECT_EQ(contact_elements(k4_force(), 0.2)(2, 2), 1.0);  // F = 0.2 at the threshold is contact
  EXPECT_EQ(contact_elements(k4_force(), 0.2001)(2, 2), 0.0);
  EXPECT_NEAR(contact_time(k4_force(), kK4ForceThreshold, 250.0), 0.02, 1e-12);
  EXPECT_EQ(contact_time(k4_force(), 2.0, 250.0), 0.0);
}

//---- Naya (K5)

TEST(NayaDescriptor, MatchesVectorK5) {
  expect_values(naya_descriptor(k4_force(), kK4ForceThreshold), {2.7, 5, 0.407407, 0.4});
  // The text's reading of eq. 14, the area at the peak load, is also 5 here.
  expect_values(naya_descriptor(k4_force(), kK4ForceThreshold, NayaArea::kAtPeakLoad),
                {2.7, 5, 0.407407, 0.4});
}

TEST(NayaDescriptor, AreaAtPeakLoadDiffersFromMaximumArea) {
  // Element 0 rises to the peak load alone after element 1, which was in contact before.
  Eigen::MatrixXd force(3, 2);
  force << 0.0, 0.5, 0.9, 0.0, 0.0, 0.0;
  expect_values(naya_descriptor(force, 0.1, NayaArea::kMaxOverTime),
                {0.9, 1, (0.9 + 0.5) / 0.9, 2.0});
  expect_values(naya_descriptor(force, 0.1, NayaArea::kAtPeakLoad),
                {0.9, 1, (0.9 + 0.5) / 0.9, 2.0});
  Eigen::MatrixXd wide(3, 3);
  wide << 0.2, 0.2, 0.2, 0.9, 0.0, 0.0, 0.0, 0.0, 0.0;
  EXPECT_EQ(naya_descriptor(wide, 0.1, NayaArea::kMaxOverTime)[1], 3.0);
  EXPECT_EQ(naya_descriptor(wide, 0.1, NayaArea::kAtPeakLoad)[1], 1.0);
}

TEST(NayaDescriptor, PeakAtTheFirstSampleComparesWithTheRestingSkin) {
  Eigen::MatrixXd force(2, 2);
  force << 1.0, 0.5, 0.2, 0.1;
  // t_max = 0: the sample before is F = 0, b = 0, so all the load and area are new.
  expect_values(naya_descriptor(force, 0.3, NayaArea::kMaxOverTime), {1.5, 2, 1.0, 1.0});
}

TEST(NayaDescriptor, NoLoadGivesZerosNotNaN) {
  expect_values(naya_descriptor(Eigen::MatrixXd::Zero(5, 4), 0.05), {0, 0, 0, 0});
  expect_values(naya_descriptor(Eigen::MatrixXd(0, 4), 0.05), {0, 0, 0, 0});
}

//---- Silvera-Tawil (K6)

TEST(SilveraTawilDescriptor, MatchesVectorK6) {
  expect_values(silvera_tawil_descriptor(k4_force(), kK4ForceThreshold, 250.0),
                {1, 0.333333, 0.119444, 0.02, 6});
}

TEST(SilveraTawilDescriptor, LiteralModesMatchVectorK6) {
  const SilveraTawilDescriptor literal =
      silvera_tawil_descriptor(k4_force(), kK4ForceThreshold, 250.0,
                               SpatialResolutionMode::kLiteral, IntensityChangeMode::kSigned);
  EXPECT_EQ(literal[1], 0.0);           // no element reaches half the peak total load
  EXPECT_NEAR(literal[4], -1.6, 1e-9);  // the signed sum telescopes
  EXPECT_NEAR(literal[2], 0.119444, 1e-6);
}

TEST(SilveraTawilDescriptor, ShortOrEmptyWindowsGiveDefinedValues) {
  Eigen::MatrixXd three(3, 2);
  three << 0.0, 0.0, 1.0, 0.5, 0.0, 0.0;
  const SilveraTawilDescriptor short_window = silvera_tawil_descriptor(three, 0.1, 100.0);
  EXPECT_EQ(short_window[4], 0.0);  // T < 4: no second difference of |ΔF|
  EXPECT_EQ(short_window[0], 1.0);
  EXPECT_EQ(short_window[1], 1.0);  // both elements >= 0.5 at t* = 1
  EXPECT_NEAR(short_window[3], 0.01, 1e-12);
  expect_values(silvera_tawil_descriptor(Eigen::MatrixXd::Zero(6, 3), 0.1, 250.0), {0, 0, 0, 0, 0});
}

//---- Koo (K7)

TEST(KooDescriptor, MatchesVectorK7) {
  // Contacted cells 1 and 2: columns ax, ay, az of each.
  Eigen::MatrixXd acceleration(8, 6);
  for (int cell = 0; cell < 2; ++cell)
    for (int t = 0; t < 8; ++t) {
      acceleration(t, 3 * cell + 0) =
          k4_cells()[static_cast<size_t>(cell)].ax[static_cast<size_t>(t)];
      acceleration(t, 3 * cell + 1) =
          k4_cells()[static_cast<size_t>(cell)].ay[static_cast<size_t>(t)];
      acceleration(t, 3 * cell + 2) =
          k4_cells()[static_cast<size_t>(cell)].az[static_cast<size_t>(t)];
    }
  const Eigen::VectorXd representative = koo_representative_acceleration(acceleration);
  const Vector expected = {1, 1.86803, 2.01167, 2.64564, 1.61803, 2.99697, 2.77635, 3.64564};
  ASSERT_EQ(representative.size(), 8);
  for (int t = 0; t < 8; ++t)
    EXPECT_NEAR(representative[t], expected[static_cast<size_t>(t)], 1e-5);
  expect_values(koo_descriptor(representative, k4_force(), kK4ForceThreshold, 250.0),
                {0.633051, 0.02, 10});
  EXPECT_EQ(koo_descriptor(representative, k4_force(), kK4ForceThreshold, 250.0,
                           ContactChangeMode::kSigned)[2],
            0.0);
}

TEST(KooDescriptor, SingleSampleGivesZeros) {
  expect_values(koo_descriptor(Eigen::VectorXd::Constant(1, 2.0),
                               Eigen::MatrixXd::Constant(1, 3, 1.0), 0.5, 250.0),
                {0, 0.004, 0});
  EXPECT_EQ(koo_representative_acceleration(Eigen::MatrixXd(0, 3)).size(), 0);
}

//---- Extractors on the K4 recording

Parameters k4_parameters() {
  Parameters parameters;
  parameters.set("f_thresh", "0.15");
  return parameters;
}

TEST(BaselineExtractors, GiveVectorsK5K6K7OnTheK4Recording) {
  const K4Recording k4 = k4_recording();
  const Label label = segment(0.0, 8 / 250.0, "front");
  const FeatureResult naya =
      make_naya_extractor(k4_parameters())->extract({k4.recording, k4.layout, label});
  ASSERT_TRUE(naya.skip_reason.empty()) << naya.skip_reason;
  expect_values(naya.values, {2.7, 5, 0.407407, 0.4});
  const FeatureResult silvera =
      make_silvera_tawil_extractor(k4_parameters())->extract({k4.recording, k4.layout, label});
  expect_values(silvera.values, {1, 0.333333, 0.119444, 0.02, 6});
  const FeatureResult koo =
      make_koo_extractor(k4_parameters())->extract({k4.recording, k4.layout, label});
  expect_values(koo.values, {0.633051, 0.02, 10});
  EXPECT_EQ(make_koo_extractor({})->columns(k4.layout).size(), 3u);
  EXPECT_EQ(make_silvera_tawil_extractor({})->columns(k4.layout)[1].name, "spatial_resolution");
}

TEST(BaselineExtractors, ContactElementsOptionDropsCellsWithoutProximityContact) {
  const K4Recording k4 = k4_recording();
  Parameters parameters = k4_parameters();
  parameters.set("elements", "contact");
  const FeatureResult silvera =
      make_silvera_tawil_extractor(parameters)
          ->extract({k4.recording, k4.layout, segment(0.0, 8 / 250.0, "front")});
  ASSERT_TRUE(silvera.skip_reason.empty()) << silvera.skip_reason;
  // Cell 3 (exactly 50 mm) is left out: 6 elements instead of 9, and cell 3 carried no force.
  EXPECT_NEAR(silvera.values[1], 3.0 / 6.0, 1e-9);
  EXPECT_NEAR(silvera.values[2], 0.119444 * 9.0 / 6.0, 1e-5);
}

TEST(BaselineExtractors, PreprocessRemovesEachSensorsRestOffset) {
  K4Recording shifted = k4_recording();
  // 0.03 N of preload on every force sensor of the front cells, visible in the 12 rest samples.
  for (int64_t cell = 1; cell <= 3; ++cell)
    for (const char* sensor : {"f1", "f2", "f3"})
      shifted.recording.streams[0]
          .samples.col(testing::nao_column(shifted.layout, cell, sensor))
          .array() += 0.03f;
  const auto naya = make_naya_extractor(k4_parameters());
  const Recording referenced = naya->preprocess(shifted.recording, shifted.layout);
  const Label label = segment(0.0, 8 / 250.0, "front");
  const FeatureResult raw = naya->extract({shifted.recording, shifted.layout, label});
  const FeatureResult result = naya->extract({referenced, shifted.layout, label});
  EXPECT_NEAR(raw.values[0], 2.7 + 9 * 0.03, 1e-5);  // without preprocessing the preload adds up
  // The median rest reading of each sensor is its 0.03 N (the 12 rest samples outnumber the
  // touched ones), so K5 comes back exactly.
  expect_values(result.values, {2.7, 5, 0.407407, 0.4});
}

TEST(RestOffset, IsTheMedianWhileNothingIsNear) {
  Eigen::VectorXf force(6), proximity(6);
  force << 0.03f, 0.9f, 0.8f, 0.02f, 0.04f, NAN;
  proximity << 200, 10, 20, 200, 120, 200;
  EXPECT_FLOAT_EQ(rest_offset(force, proximity, 50.0), 0.03f);
  proximity.setConstant(10.0f);  // always touched: fall back to the smallest reading
  EXPECT_FLOAT_EQ(rest_offset(force, proximity, 50.0), 0.02f);
  EXPECT_EQ(rest_offset(Eigen::VectorXf(), Eigen::VectorXf(), 50.0), 0.0f);
}

TEST(BaselineExtractors, SkipNoContactNonFiniteForceAndUnknownRegion) {
  K4Recording k4 = k4_recording();
  for (const auto& extractor :
       {make_naya_extractor({}), make_silvera_tawil_extractor({}), make_koo_extractor({})}) {
    EXPECT_EQ(
        extractor->extract({k4.recording, k4.layout, segment(10 / 250.0, 19 / 250.0, "front")})
            .skip_reason,
        "no cell in contact")
        << extractor->name();
    EXPECT_FALSE(extractor->extract({k4.recording, k4.layout, segment(0.0, 8 / 250.0, "left-arm")})
                     .skip_reason.empty());
  }
  // A NaN in cell 3's force is read by the baselines (all elements), not by Kaboli's descriptor.
  k4.recording.streams[0].samples(2, testing::nao_column(k4.layout, 3, "f2")) = NAN;
  const FeatureResult naya =
      make_naya_extractor({})->extract({k4.recording, k4.layout, segment(0.0, 8 / 250.0, "front")});
  EXPECT_NE(naya.skip_reason.find("c03.f2"), std::string::npos) << naya.skip_reason;
  // Koo also reads the accelerometers of the contacted cells.
  K4Recording other = k4_recording();
  other.recording.streams[0].samples(5, testing::nao_column(other.layout, 1, "az")) = INFINITY;
  const FeatureResult koo = make_koo_extractor({})->extract(
      {other.recording, other.layout, segment(0.0, 8 / 250.0, "front")});
  EXPECT_NE(koo.skip_reason.find("c01.az"), std::string::npos) << koo.skip_reason;
}

TEST(BaselineExtractors, BadParametersNameTheKey) {
  Parameters zero_threshold;
  zero_threshold.set("f_thresh", "0");
  EXPECT_THROW(make_naya_extractor(zero_threshold), Error);
  Parameters bad_mode;
  bad_mode.set("roi_mode", "squared");
  try {
    make_silvera_tawil_extractor(bad_mode);
    FAIL();
  } catch (const Error& error) {
    EXPECT_NE(error.message().find("roi_mode"), std::string::npos) << error.what();
  }
  Parameters foreign;
  foreign.set("naya_area", "MAX");
  EXPECT_THROW(make_koo_extractor(foreign), Error);  // a Naya option is a typo for Koo
}

}  // namespace
}  // namespace tactile
