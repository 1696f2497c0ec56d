#include <gtest/gtest.h>
#include <imgui.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "osmesa_renderer.h"
#include "render_test_support.h"
#include "tactile/widgets/signal_plot.h"

namespace tactile {
namespace {

using testing::begin_canvas;
using testing::close_to_packed;
using testing::end_canvas;

constexpr double kRate = 1000.0;    // Hz
constexpr double kFrequency = 0.5;  // Hz: peak at 0.5 s, trough at 1.5 s
constexpr float kAmplitude = 2.0f;
constexpr uint32_t kSineColour = IM_COL32(255, 64, 64, 255);

std::vector<float> sine(int64_t count) {
  std::vector<float> samples(count);
  for (int64_t index = 0; index < count; ++index) {
    samples[index] = kAmplitude * static_cast<float>(std::sin(2.0 * std::numbers::pi * kFrequency *
                                                              static_cast<double>(index) / kRate));
  }
  return samples;
}

// One channel at kRate starting at `start_time`, held in memory.
std::unique_ptr<MemorySampleSource> source_of(const std::vector<float>& samples,
                                              double start_time = 0.0) {
  Stream stream;
  stream.name = "test";
  stream.rate_hz = kRate;
  stream.start_time = start_time;
  stream.channels = {"x"};
  stream.samples =
      Eigen::Map<const SampleMatrix>(samples.data(), static_cast<Eigen::Index>(samples.size()), 1);
  return std::make_unique<MemorySampleSource>(std::move(stream));
}

struct PlotFixture : ::testing::Test {
  OffscreenRenderer renderer{800, 400};
  std::vector<float> samples = sine(10'000);  // 10 s
  std::unique_ptr<MemorySampleSource> source = source_of(samples);
  std::vector<PlotChannel> channels{{"sine", source.get(), 0, kSineColour}};

  SignalPlotResult frame(SignalPlotState& state, double cursor_time = -1.0,
                         std::span<const PlotSpan> spans = {}) {
    renderer.new_frame();
    begin_canvas(renderer);
    const SignalPlotResult result =
        draw_signal_plot("plot", channels, spans, state, cursor_time, ImVec2(800, 400));
    end_canvas();
    return result;
  }
  float x_of(const SignalPlotResult& result, const SignalPlotState& state, double t) const {
    return result.area_min.x +
           static_cast<float>((t - state.view_t0) / (state.view_t1 - state.view_t0)) *
               (result.area_max.x - result.area_min.x);
  }
};

// Rows of the data area at column x holding the sine's colour, as fractions of
// the area's height from the top.
std::vector<float> coloured_rows(const Image& image, const SignalPlotResult& result, int x) {
  std::vector<float> rows;
  const int top = static_cast<int>(result.area_min.y);
  const int bottom = static_cast<int>(result.area_max.y);
  for (int y = top; y < bottom; ++y) {
    if (close_to_packed(image.at(x, y), kSineColour, 12)) {
      rows.push_back(static_cast<float>(y - top) / static_cast<float>(bottom - top));
    }
  }
  return rows;
}

TEST_F(PlotFixture, SinePeakIsDrawnNearTheTopAndTroughNearTheBottom) {
  SignalPlotState state{.view_t0 = 0.0, .view_t1 = 4.0, .fitted = true};
  const std::vector<PlotSpan> spans = {{2.5, 3.0, IM_COL32(60, 120, 255, 90), "stroke"}};
  const SignalPlotResult result = frame(state, 3.25, spans);
  const Image image = renderer.render();
  write_png(testing::png_path("sine_plot"), image);

  // Auto-fitted value range: the amplitude plus 5 % headroom.
  EXPECT_NEAR(result.value_min, -2.2, 1e-3);
  EXPECT_NEAR(result.value_max, 2.2, 1e-3);

  const int peak = static_cast<int>(x_of(result, state, 0.5));
  const std::vector<float> at_peak = coloured_rows(image, result, peak);
  ASSERT_FALSE(at_peak.empty());
  // 2.0 of [-2.2, 2.2] sits 0.045 of the height below the top.
  EXPECT_LT(at_peak.front(), 0.08f);
  EXPECT_GT(at_peak.front(), 0.02f);
  EXPECT_LT(at_peak.back(), 0.1f);  // nothing near the middle or bottom

  const int trough = static_cast<int>(x_of(result, state, 1.5));
  const std::vector<float> at_trough = coloured_rows(image, result, trough);
  ASSERT_FALSE(at_trough.empty());
  EXPECT_GT(at_trough.back(), 0.92f);
  EXPECT_GT(at_trough.front(), 0.9f);

  // Zero crossing at 1.0 s: the line passes the middle.
  const std::vector<float> at_zero =
      coloured_rows(image, result, static_cast<int>(x_of(result, state, 1.0)));
  ASSERT_FALSE(at_zero.empty());
  EXPECT_NEAR(at_zero.front(), 0.5f, 0.05f);

  // The time cursor at 3.25 s is drawn in orange across the area (anti-aliased:
  // look at the pixels either side of its position).
  const int cursor = static_cast<int>(x_of(result, state, 3.25));
  bool orange = false;
  for (int x = cursor - 1; x <= cursor + 1; ++x) {
    orange |= close_to_packed(image.at(x, static_cast<int>(result.area_max.y) - 5),
                              IM_COL32(255, 140, 40, 255), 30);
  }
  EXPECT_TRUE(orange);

  // The label span [2.5, 3.0) is shaded blue where the sine does not pass.
  const Image::Rgba shaded = image.at(static_cast<int>(x_of(result, state, 2.75)),
                                      static_cast<int>(result.area_max.y) - 5);
  const Image::Rgba plain = image.at(static_cast<int>(x_of(result, state, 2.25)),
                                     static_cast<int>(result.area_max.y) - 5);
  EXPECT_GT(shaded.b, plain.b + 20);
}

TEST_F(PlotFixture, ZoomedInSamplesAreDrawnAsALine) {
  // 0.2 s over ~740 pixels: fewer samples than pixels.
  SignalPlotState state{.view_t0 = 0.4, .view_t1 = 0.6, .fitted = true};
  const SignalPlotResult result = frame(state);
  const Image image = renderer.render();
  write_png(testing::png_path("sine_plot_zoomed"), image);
  // The values over [0.4, 0.6] s span [1.90, 2.0]; fitted to that range, the peak
  // is at the top and 0.41 s (1.92) about 0.78 of the height down.
  const std::vector<float> rows =
      coloured_rows(image, result, static_cast<int>(x_of(result, state, 0.5)));
  ASSERT_FALSE(rows.empty());
  EXPECT_LT(rows.front(), 0.1f);
  const std::vector<float> edge =
      coloured_rows(image, result, static_cast<int>(x_of(result, state, 0.41)));
  ASSERT_FALSE(edge.empty());
  EXPECT_GT(edge.front(), 0.7f);
}

TEST_F(PlotFixture, StackedLanesGiveEachChannelItsOwnBand) {
  // A second channel, the sine upside down and in another colour: stacked, the
  // first lives in the top half and the second in the bottom half.
  std::vector<float> inverted = samples;
  for (float& value : inverted) value = -value;
  const auto inverted_source = source_of(inverted);
  const uint32_t inverted_colour = IM_COL32(64, 220, 64, 255);
  channels.push_back({"inverted", inverted_source.get(), 0, inverted_colour});
  SignalPlotState state{.view_t0 = 0.0, .view_t1 = 4.0, .fitted = true, .stacked = true};
  const SignalPlotResult result = frame(state);
  const Image image = renderer.render();
  write_png(testing::png_path("sine_plot_stacked"), image);
  const int peak = static_cast<int>(x_of(result, state, 0.5));
  const std::vector<float> first = coloured_rows(image, result, peak);
  ASSERT_FALSE(first.empty());
  EXPECT_LT(first.back(), 0.1f);  // top of the top lane
  int lowest_inverted = -1;
  for (int y = static_cast<int>(result.area_min.y); y < static_cast<int>(result.area_max.y); ++y) {
    if (close_to_packed(image.at(peak, y), inverted_colour, 12)) lowest_inverted = y;
  }
  ASSERT_GE(lowest_inverted, 0);
  // The inverted peak is the bottom of the bottom lane.
  const float fraction =
      (lowest_inverted - result.area_min.y) / (result.area_max.y - result.area_min.y);
  EXPECT_GT(fraction, 0.9f);
}

TEST(SignalPlot, VertexCountStaysBoundedForTenMillionSamples) {
  OffscreenRenderer renderer(800, 300);
  const std::vector<float> samples = sine(10'000'000);
  const auto a = source_of(samples);
  const auto b = source_of(samples, 5.0);
  const std::vector<PlotChannel> channels = {{"a", a.get(), 0, 0}, {"b", b.get(), 0, 0}};
  for (double span : {10'005.0, 100.0, 1.0}) {
    SignalPlotState state{.view_t0 = 0.0, .view_t1 = span, .fitted = true};
    renderer.new_frame();
    begin_canvas(renderer);
    const SignalPlotResult result =
        draw_signal_plot("plot", channels, {}, state, 0.0, ImVec2(800, 300));
    end_canvas();
    const Image image = renderer.render();
    if (span > 1000) write_png(testing::png_path("sine_plot_ten_million"), image);
    // Two channels of one bar (4 vertices) per column, plus ticks, labels and legend.
    const int width = static_cast<int>(result.area_max.x - result.area_min.x);
    EXPECT_LE(result.vertices, 2 * 4 * width + 3000) << "span " << span;
    EXPECT_GE(result.vertices, 2 * width) << "span " << span;  // the data is really drawn
  }
}

//---- Mouse

struct MouseFixture : PlotFixture {
  void move(float x, float y, bool down, float wheel = 0.0f) {
    ImGuiIO& io = ImGui::GetIO();
    io.MousePos = ImVec2(x, y);
    io.MouseDown[0] = down;
    io.MouseWheel = wheel;
  }
};

TEST_F(MouseFixture, WheelZoomsAboutTheCursor) {
  SignalPlotState state{.view_t0 = 0.0, .view_t1 = 4.0, .fitted = true};
  move(10, 10, false);
  SignalPlotResult result = frame(state);  // let ImGui learn the window
  renderer.render();
  const float x = x_of(result, state, 1.0);
  move(x, 200, false, 1.0f);
  result = frame(state);
  renderer.render();
  EXPECT_TRUE(result.view_changed);
  EXPECT_NEAR(state.view_t1 - state.view_t0, 4.0 * 0.8, 1e-9);
  // The time under the mouse stays put: 1.0 s is still at x.
  EXPECT_NEAR(x_of(result, state, 1.0), x, 0.01f);
  EXPECT_GT(state.view_t0, 0.0);
}

TEST_F(MouseFixture, ClickReturnsTheTimeUnderTheMouse) {
  SignalPlotState state{.view_t0 = 0.0, .view_t1 = 4.0, .fitted = true};
  move(10, 10, false);
  SignalPlotResult result = frame(state);
  renderer.render();
  const float x = x_of(result, state, 2.5);
  move(x, 200, false);
  frame(state);
  renderer.render();
  move(x, 200, true);
  result = frame(state);
  renderer.render();
  EXPECT_FALSE(result.clicked_time.has_value());  // pressed, not yet released
  move(x, 200, false);
  result = frame(state);
  renderer.render();
  ASSERT_TRUE(result.clicked_time.has_value());
  EXPECT_NEAR(*result.clicked_time, 2.5, 4.0 / 700);
  EXPECT_DOUBLE_EQ(state.view_t0, 0.0);  // a click does not move the view
}

TEST_F(MouseFixture, DragPansAndDoesNotClick) {
  SignalPlotState state{.view_t0 = 0.0, .view_t1 = 4.0, .fitted = true};
  move(10, 10, false);
  SignalPlotResult result = frame(state);
  renderer.render();
  const float width = result.area_max.x - result.area_min.x;
  move(400, 200, false);
  frame(state);
  renderer.render();
  bool clicked = false;
  for (float x = 400; x >= 300; x -= 20) {  // drag 100 px to the left
    move(x, 200, true);
    clicked |= frame(state).clicked_time.has_value();
    renderer.render();
  }
  move(300, 200, false);
  clicked |= frame(state).clicked_time.has_value();
  renderer.render();
  EXPECT_FALSE(clicked);
  // Dragging left by 100 px moves the view later by 100 px worth of time; the
  // first few pixels only cross the drag threshold.
  EXPECT_NEAR(state.view_t0, 100.0 / width * 4.0, 4.0 / width * 1.01);
  EXPECT_NEAR(state.view_t1 - state.view_t0, 4.0, 1e-9);
}

TEST_F(MouseFixture, DoubleClickFitsAllData) {
  SignalPlotState state{.view_t0 = 1.0, .view_t1 = 2.0, .fitted = true};
  move(10, 10, false);
  frame(state);
  renderer.render();
  for (bool down : {false, true, false, true}) {
    move(400, 200, down);
    frame(state);
    renderer.render();
  }
  EXPECT_DOUBLE_EQ(state.view_t0, 0.0);
  EXPECT_DOUBLE_EQ(state.view_t1, 10.0);  // 10 000 samples at 1 kHz
}

TEST(SignalPlotTicks, StepsAreOneTwoOrFiveTimesAPowerOfTen) {
  EXPECT_DOUBLE_EQ(nice_tick_step(10.0, 5), 2.0);
  EXPECT_DOUBLE_EQ(nice_tick_step(1.0, 4), 0.5);
  EXPECT_DOUBLE_EQ(nice_tick_step(3600.0, 8), 500.0);
  EXPECT_NEAR(nice_tick_step(0.003, 3), 0.001, 1e-15);
  EXPECT_DOUBLE_EQ(nice_tick_step(0.0, 5), 1.0);
}

}  // namespace
}  // namespace tactile
