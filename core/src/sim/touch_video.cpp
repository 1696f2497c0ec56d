#include "tactile/sim/touch_video.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "tactile/error.h"
#include "tactile/random.h"
#include "tactile/video/video_writer.h"

namespace tactile {

namespace {

constexpr double kReachSeconds = 0.25;  // the hand's way onto the skin and back
constexpr double kPi = 3.14159265358979323846;

struct Canvas {
  int width, height;
  std::vector<uint8_t> rgba;
  void fill(std::array<uint8_t, 3> colour) {
    for (size_t p = 0; p < rgba.size(); p += 4) {
      rgba[p] = colour[0], rgba[p + 1] = colour[1], rgba[p + 2] = colour[2], rgba[p + 3] = 255;
    }
  }
  // A filled ellipse, soft at its edge.
  void ellipse(double cx, double cy, double rx, double ry, std::array<uint8_t, 3> colour) {
    const int x0 = std::max(0, static_cast<int>(cx - rx - 1)),
              x1 = std::min(width - 1, static_cast<int>(cx + rx + 1));
    const int y0 = std::max(0, static_cast<int>(cy - ry - 1)),
              y1 = std::min(height - 1, static_cast<int>(cy + ry + 1));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double dx = (x + 0.5 - cx) / rx, dy = (y + 0.5 - cy) / ry;
        const double inside = std::clamp((1.0 - std::sqrt(dx * dx + dy * dy)) * rx, 0.0, 1.0);
        if (inside <= 0.0) continue;
        uint8_t* pixel = &rgba[(static_cast<size_t>(y) * width + x) * 4];
        for (int c = 0; c < 3; ++c)
          pixel[c] = static_cast<uint8_t>(pixel[c] + inside * (colour[c] - pixel[c]));
      }
  }
};

// Where the hand is at recording time `time` (canvas pixels), and how far it is pressed in
// (0 resting, 1 on the skin).
struct HandPlace {
  double x, y, on;
};

struct Placed {
  double t0, t1, x, y;
  std::string class_name;
};

HandPlace hand_at(double time, const std::vector<Placed>& touches, double rest_x, double rest_y,
                  double reach) {
  for (const Placed& touch : touches) {
    if (time < touch.t0 - kReachSeconds || time > touch.t1 + kReachSeconds) continue;
    const double on = time < touch.t0   ? 1.0 - (touch.t0 - time) / kReachSeconds
                      : time > touch.t1 ? 1.0 - (time - touch.t1) / kReachSeconds
                                        : 1.0;
    double x = touch.x, y = touch.y;
    const double into = std::max(0.0, time - touch.t0);
    const std::string& kind = touch.class_name;
    // Strokes and rubs move along the skin; the quick touches bob.
    if (kind.find("stroke") != std::string::npos || kind.find("rub") != std::string::npos ||
        kind.find("scratch") != std::string::npos || kind.find("tickl") != std::string::npos)
      x += 0.6 * reach * std::sin(2.0 * kPi * 1.5 * into);
    else
      y += 0.15 * reach * std::sin(2.0 * kPi * 4.0 * into);
    const double eased = 0.5 - 0.5 * std::cos(kPi * std::clamp(on, 0.0, 1.0));
    return {rest_x + eased * (x - rest_x), rest_y + eased * (y - rest_y), eased};
  }
  return {rest_x, rest_y, 0.0};
}

}  // namespace

void write_touch_video(const std::string& path, const SkinLayout& layout,
                       const std::vector<Label>& touches, const TouchVideoOptions& options) {
  if (options.width < 16 || options.height < 16 || options.width % 2 || options.height % 2)
    throw Error(path, "a touch video's size must be even and at least 16 x 16");
  if (!(options.rate > 0.0) || !(options.duration > 0.0))
    throw Error(path, "a touch video needs a positive rate and duration");
  Canvas canvas{options.width, options.height,
                std::vector<uint8_t>(static_cast<size_t>(options.width) * options.height * 4)};
  // The map fitted into the picture's left four fifths, the person's edge on the right.
  const std::pair<Point2, Point2> box = layout.bounds();
  const Point2 low = box.first, high = box.second;
  const double map_width = std::max(1e-9, high.x - low.x),
               map_height = std::max(1e-9, high.y - low.y);
  const double scale =
      std::min(0.72 * options.width / map_width, 0.8 * options.height / map_height);
  const double left = 0.06 * options.width, top = 0.1 * options.height;
  auto to_canvas = [&](Point2 point) {
    return std::pair{left + (point.x - low.x) * scale, top + (point.y - low.y) * scale};
  };
  const double reach = 0.12 * std::min(options.width, options.height);
  std::vector<Placed> placed;
  for (const Label& touch : touches) {
    const Group* group = layout.find_group(touch.region);
    double x = 0, y = 0;
    int count = 0;
    for (const Taxel& taxel : layout.taxels)
      if (!group ||
          std::find(group->taxels.begin(), group->taxels.end(), taxel.id) != group->taxels.end()) {
        const auto [cx, cy] = to_canvas(taxel.position);
        x += cx, y += cy, ++count;
      }
    if (count == 0) continue;
    placed.push_back({touch.t0, touch.t1, x / count, y / count, touch.class_name});
  }
  std::sort(placed.begin(), placed.end(),
            [](const Placed& a, const Placed& b) { return a.t0 < b.t0; });
  const double rest_x = 0.8 * options.width, rest_y = 0.92 * options.height;

  VideoWriterOptions writer_options;
  writer_options.width = options.width;
  writer_options.height = options.height;
  writer_options.rate = options.rate;
  writer_options.codec = options.codec;
  VideoWriter writer(path, writer_options);
  Random random{std::mt19937_64(options.seed)};
  const double sway_phase = random.uniform() * 2.0 * kPi;
  const int64_t frames = static_cast<int64_t>(std::ceil(options.duration * options.rate));
  for (int64_t k = 0; k < frames; ++k) {
    const double video_time = static_cast<double>(k) / options.rate;
    const double time = options.offset + video_time;
    canvas.fill({58, 62, 70});
    // The skin: its taxels as pale dots.
    const double dot = std::max(1.5, 0.012 * options.width);
    for (const Taxel& taxel : layout.taxels) {
      const auto [x, y] = to_canvas(taxel.position);
      canvas.ellipse(x, y, dot, dot, {150, 160, 175});
    }
    // A person at the edge, swaying slowly: motion that is not touch.
    const double sway = options.sway * 0.04 * options.width *
                        std::sin(2.0 * kPi * 0.13 * time + sway_phase) *
                        (1.0 + 0.5 * std::sin(2.0 * kPi * 0.031 * time));
    canvas.ellipse(0.93 * options.width + sway, 0.35 * options.height, 0.06 * options.width,
                   0.3 * options.height, {90, 80, 110});
    // The hand and its fingers, pointing at where it touches.
    const HandPlace hand = hand_at(time, placed, rest_x, rest_y, reach);
    const double palm = reach * (0.55 + 0.1 * hand.on);
    canvas.ellipse(hand.x, hand.y + 0.35 * palm, palm, 0.8 * palm, {214, 170, 140});
    for (int finger = 0; finger < 4; ++finger) {
      const double fx = hand.x + (finger - 1.5) * 0.42 * palm;
      canvas.ellipse(fx, hand.y - 0.45 * palm, 0.17 * palm, 0.45 * palm, {224, 182, 152});
    }
    if (options.noise > 0.0)
      for (size_t p = 0; p < canvas.rgba.size(); p += 4) {
        const double shift = options.noise * (random.uniform() - 0.5) * 2.0;
        for (int c = 0; c < 3; ++c)
          canvas.rgba[p + c] =
              static_cast<uint8_t>(std::clamp(canvas.rgba[p + c] + shift, 0.0, 255.0));
      }
    writer.write(canvas.rgba.data(), video_time);
  }
  writer.finish();
}

}  // namespace tactile
