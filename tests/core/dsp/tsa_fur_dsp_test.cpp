// Preprocessing of the TSA (spec §2.2-2.3) and smart-fur (spec §3.2-3.3) pipelines.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "tactile/dsp/contact_trigger.h"
#include "tactile/dsp/high_pass.h"
#include "tactile/dsp/iir_average.h"
#include "tactile/error.h"

namespace tactile {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Eigen::VectorXd vector_of(std::vector<double> values) {
  return Eigen::Map<Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

void expect_near_all(const Eigen::VectorXd& actual, const std::vector<double>& expected,
                     double tolerance) {
  ASSERT_EQ(actual.size(), static_cast<Eigen::Index>(expected.size()));
  for (size_t k = 0; k < expected.size(); ++k)
    EXPECT_NEAR(actual[static_cast<Eigen::Index>(k)], expected[k], tolerance) << "index " << k;
}

//---- TSA eq. (3) -------------------------------------------------------------------------

TEST(IirAverage, FloatingFormMatchesSpecVectorT1) {
  expect_near_all(dsp::iir_average(vector_of({0, 8, 8, 8, 0, 0}), 4),
                  {0, 2, 3.5, 4.625, 3.46875, 2.60156}, 1e-5);
}

TEST(IirAverage, FirmwareFormTruncatesAsSpecVectorT1) {
  const std::vector<int64_t> values = {0, 8, 8, 8, 0, 0};
  EXPECT_EQ(dsp::iir_average_integer(values, 4), (std::vector<int64_t>{0, 2, 3, 4, 3, 2}));
}

TEST(IirAverage, WindowOfOnePassesTheSignalThrough) {
  expect_near_all(dsp::iir_average(vector_of({3, -1, 7}), 1), {3, -1, 7}, 0.0);
}

TEST(IirAverage, RejectsAWindowThatIsNotAPowerOfTwo) {
  EXPECT_THROW(dsp::iir_average(vector_of({1, 2}), 3), Error);
  EXPECT_THROW(dsp::iir_average(vector_of({1, 2}), 0), Error);
}

TEST(IirAverage, MissingSampleIsNaNAndDoesNotPoisonLaterFrames) {
  const Eigen::VectorXd smoothed = dsp::iir_average(vector_of({kNaN, 4, kNaN, 8}), 4);
  EXPECT_TRUE(std::isnan(smoothed[0]));
  EXPECT_DOUBLE_EQ(smoothed[1], 4.0);  // the state starts at the first finite sample
  EXPECT_TRUE(std::isnan(smoothed[2]));
  EXPECT_DOUBLE_EQ(smoothed[3], 5.0);  // 4 + (8 - 4) / 4, as if frame 2 had not been read
}

TEST(IirAverage, SmoothsEachColumnOfAMatrixOnItsOwn) {
  SampleMatrix samples(3, 2);
  samples << 0, 100, 8, 100, 8, 0;
  const SampleMatrix smoothed = dsp::iir_average_columns(samples, 2);
  EXPECT_FLOAT_EQ(smoothed(2, 0), 6.0f);   // 0 -> 4 -> 6
  EXPECT_FLOAT_EQ(smoothed(2, 1), 50.0f);  // 100 -> 100 -> 50
}

//---- TSA baseline and trigger (§2.3) -----------------------------------------------------

// Two sheets of two pads each, 8 Hz; pad 0 is touched by +40 counts at frames 30..33.
SampleMatrix touched_sheets(int64_t frames) {
  SampleMatrix samples(frames, 4);
  for (int64_t frame = 0; frame < frames; ++frame) {
    const float wobble = (frame % 2 == 0) ? 0.5f : -0.5f;
    samples(frame, 0) = 500.0f + wobble + ((frame >= 30 && frame <= 33) ? 40.0f : 0.0f);
    samples(frame, 1) = 420.0f - wobble;
    samples(frame, 2) = 610.0f + wobble;
    samples(frame, 3) = 380.0f;
  }
  return samples;
}

TEST(ContactTrigger, TouchAboveBaselineClearsTheThresholdOnlyWhereTouched) {
  const dsp::ContactTrigger trigger =
      dsp::contact_trigger(touched_sheets(60), {{0, 1}, {2, 3}}, {});
  // Noise of ±0.5 counts: 5 robust sigmas (3.7) clear the 3-count floor; a still pad gets the
  // floor.
  EXPECT_NEAR(trigger.thresholds[0], 5.0 * 1.4826 * 0.5, 1e-6);
  EXPECT_DOUBLE_EQ(trigger.thresholds[3], 3.0);
  EXPECT_NEAR(trigger.contact(31, 0), 40.0, 0.6);
  EXPECT_EQ(trigger.contact(29, 0), 0.0f);
  EXPECT_EQ(trigger.contact(34, 0), 0.0f);
  for (int column = 1; column < 4; ++column)
    EXPECT_EQ(trigger.contact.col(column).cwiseAbs().maxCoeff(), 0.0f) << "column " << column;
}

TEST(ContactTrigger, FallingCountsTriggerWhenTheSignIsFalling) {
  SampleMatrix samples = touched_sheets(60);
  samples.col(0) = (1000.0f - samples.col(0).array()).matrix();
  dsp::ContactTriggerOptions options;
  options.rising = false;
  const dsp::ContactTrigger trigger = dsp::contact_trigger(samples, {{0, 1}}, options);
  EXPECT_NEAR(trigger.contact(31, 0), 40.0, 0.6);
  options.rising = true;
  EXPECT_EQ(dsp::contact_trigger(samples, {{0, 1}}, options).contact(31, 0), 0.0f);
}

TEST(ContactTrigger, BaselineFollowsSlowDriftWhileTheSheetIsIdle) {
  // 20 counts of drift over 100 s would trigger forever against a fixed baseline.
  const int64_t frames = 800;
  SampleMatrix samples(frames, 1);
  for (int64_t frame = 0; frame < frames; ++frame) samples(frame, 0) = 300.0f + 0.025f * frame;
  const dsp::ContactTrigger trigger = dsp::contact_trigger(samples, {{0}}, {});
  EXPECT_EQ(trigger.contact.cwiseAbs().maxCoeff(), 0.0f);
}

TEST(ContactTrigger, BaselineHoldsDuringALongTouch) {
  // A 10 s press: a baseline that followed it would let the contact fade away.
  SampleMatrix samples = SampleMatrix::Constant(200, 1, 500.0f);
  samples.block(40, 0, 80, 1).array() += 30.0f;
  const dsp::ContactTrigger trigger = dsp::contact_trigger(samples, {{0}}, {});
  EXPECT_NEAR(trigger.contact(119, 0), 30.0, 1e-4);
  EXPECT_EQ(trigger.contact(120, 0), 0.0f);
}

TEST(ContactTrigger, MissingSampleStaysNaNAndIsNotAContact) {
  SampleMatrix samples = touched_sheets(60);
  samples(31, 0) = std::numeric_limits<float>::quiet_NaN();
  const dsp::ContactTrigger trigger = dsp::contact_trigger(samples, {{0, 1}}, {});
  EXPECT_TRUE(std::isnan(trigger.contact(31, 0)));
  EXPECT_NEAR(trigger.contact(32, 0), 40.0, 0.6);
}

TEST(ContactTrigger, RejectsAColumnOutsideTheMatrix) {
  EXPECT_THROW(dsp::contact_trigger(touched_sheets(10), {{0, 7}}, {}), Error);
}

//---- Smart fur high-pass and calibration (§3.2-3.3) --------------------------------------

TEST(HighPass, CoefficientOfPointTwoHertzAtFifteenHertzMatchesSpecVectorF1) {
  EXPECT_NEAR(dsp::high_pass_coefficient(0.2, 15.0), 0.9227, 1e-4);
}

TEST(HighPass, StepResponseMatchesSpecVectorF1) {
  expect_near_all(
      dsp::high_pass(vector_of({0, 0, 1, 1, 1, 1, 1, 0, 0, 0}), 0.2, 15.0),
      {0, 0, 0.9227, 0.851375, 0.785564, 0.72484, 0.66881, -0.305589, -0.281967, -0.260171}, 1e-5);
}

TEST(HighPass, ConstantOffsetGivesZeroFromTheFirstSample) {
  expect_near_all(dsp::high_pass(vector_of({700, 700, 700}), 0.2, 15.0), {0, 0, 0}, 0.0);
}

TEST(HighPass, MissingSampleIsNaNAndSkipped) {
  const Eigen::VectorXd filtered = dsp::high_pass(vector_of({0, kNaN, 1}), 0.2, 15.0);
  EXPECT_TRUE(std::isnan(filtered[1]));
  EXPECT_NEAR(filtered[2], 0.9227, 1e-4);  // as if the step came right after sample 0
}

TEST(HighPass, RejectsANonPositiveCutOffOrRate) {
  EXPECT_THROW(dsp::high_pass_coefficient(0.0, 15.0), Error);
  EXPECT_THROW(dsp::high_pass_coefficient(0.2, -1.0), Error);
}

TEST(Calibration, NormalisedStepMatchesSpecVectorF1) {
  const Eigen::VectorXd filtered =
      dsp::high_pass(vector_of({0, 0, 1, 1, 1, 1, 1, 0, 0, 0}), 0.2, 15.0);
  const SampleMatrix samples = filtered.cast<float>();
  const std::vector<double> peaks = {0.8};
  const SampleMatrix normalised = dsp::normalise_to_calibration(samples, peaks);
  expect_near_all(normalised.col(0).cast<double>(),
                  {0, 0, 1, 1, 0.981955, 0.90605, 0.836012, 0, 0, 0}, 1e-5);
}

TEST(Calibration, DeadCellReadsZeroAndMissingSampleStaysNaN) {
  SampleMatrix samples(2, 2);
  samples << 5.0f, 0.25f, std::numeric_limits<float>::quiet_NaN(), 0.5f;
  const std::vector<double> peaks = {0.0, 1.0};
  const SampleMatrix normalised = dsp::normalise_to_calibration(samples, peaks);
  EXPECT_EQ(normalised(0, 0), 0.0f);
  EXPECT_TRUE(std::isnan(normalised(1, 0)));
  EXPECT_FLOAT_EQ(normalised(1, 1), 0.5f);
}

TEST(Calibration, RejectsAPeakCountThatDoesNotMatchTheChannels) {
  const std::vector<double> peaks = {1.0};
  EXPECT_THROW(dsp::normalise_to_calibration(SampleMatrix::Zero(3, 2), peaks), Error);
}

}  // namespace
}  // namespace tactile
