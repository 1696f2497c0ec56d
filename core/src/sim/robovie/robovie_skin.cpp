// The Robovie-IIF skin as a sensor: film geometry from the layout, contact patches
// pressing on films, joints bending the skin, and the piezo films' high-pass response.

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "tactile/error.h"
#include "tactile/sim/robovie_sim.h"

namespace tactile::sim::robovie {

namespace {

// A ramp max(u, 0) whose corner is rounded over [-blur, blur]: a ramp convolved with a box
// of width 2*blur. It keeps the overlap below continuous in its first derivative, as the
// silicone between hand and film smooths the pressure's edge.
double soft_ramp(double u, double blur) {
  if (u >= blur) return u;
  if (u <= -blur) return 0.0;
  return (u + blur) * (u + blur) / (4.0 * blur);
}

// Length of overlap of a patch interval (half-width `patch`) and a film interval
// (half-width `film`) whose centres are `distance` apart: the trapezoid of two boxes
// convolved, built from four ramps.
double soft_overlap(double distance, double patch, double film, double blur) {
  return soft_ramp(distance + patch + film, blur) - soft_ramp(distance + patch - film, blur) -
         soft_ramp(distance - patch + film, blur) + soft_ramp(distance - patch - film, blur);
}

constexpr double kSiliconeBlur = 6.0;  // mm: how far the soft skin spreads a pressure edge

// The films are "embedded in soft silicone rubber" (paper 003, Sec. IV-A): a press deforms
// the rubber around it, so the films beside the pressed one carry part of its load, less the
// farther they lie ("distant sensors usually have low correlated signals", Sec. III). A film
// 40 mm away (the next 3 cm film) carries 18 % of the load, one 80 mm away 7 %.
constexpr double kSpreadShare = 0.5;
constexpr double kSpreadReach = 40.0;  // mm, over which the carried share falls by e

// How strongly each joint bends the skin of each body part (1 = the films right over it).
// Parts not named take kWholeBodyCoupling: the whole shell shakes a little.
constexpr double kWholeBodyCoupling = 0.05;
const std::map<std::string, double>& joint_weights(Joint joint) {
  static const std::map<std::string, double> head = {{"neck", 1.0},
                                                     {"head", 0.35},
                                                     {"face", 0.35},
                                                     {"shoulder-right", 0.25},
                                                     {"shoulder-left", 0.25}};
  static const std::map<std::string, double> right_arm = {
      {"shoulder-right", 1.0}, {"upper-arm-right", 0.8}, {"forearm-right", 0.45},
      {"hand-right", 0.25},    {"side-right", 0.3},      {"chest-upper", 0.12},
      {"back-upper", 0.12}};
  static const std::map<std::string, double> left_arm = {
      {"shoulder-left", 1.0}, {"upper-arm-left", 0.8}, {"forearm-left", 0.45}, {"hand-left", 0.25},
      {"side-left", 0.3},     {"chest-upper", 0.12},   {"back-upper", 0.12}};
  static const std::map<std::string, double> waist = {
      {"hip-right", 0.7},  {"hip-left", 0.7},  {"chest-lower", 0.3},  {"back-lower", 0.3},
      {"side-right", 0.3}, {"side-left", 0.3}, {"thigh-right", 0.35}, {"thigh-left", 0.35}};
  switch (joint) {
    case Joint::kHead:
      return head;
    case Joint::kRightArm:
      return right_arm;
    case Joint::kLeftArm:
      return left_arm;
    case Joint::kWaist:
      return waist;
  }
  return head;
}

constexpr double kBendingLoad = 0.5;         // N of film load per rad of joint angle, at weight 1
constexpr double kMotorVibration = 35.0;     // counts RMS per rad/s of joint speed, at weight 1
constexpr double kCountsPerNewton = 1500.0;  // charge amplifier gain over a film's force step

// The 16-bit signed A/D: one count per level, saturating at the rails. Same levels as
// sim::quantize over [kAdcLow, kAdcHigh] with 16 bits, without its per-call scaling.
float adc_counts(double value) {
  return static_cast<float>(std::round(std::clamp(value, kAdcLow, kAdcHigh)));
}

}  // namespace

//---- Films of a layout

Films films_of(const SkinLayout& layout) {
  const std::string where = "layout " + layout.id;
  const int modality = layout.modality_index("piezo");
  if (modality < 0)
    throw Error(where, "has no \"piezo\" modality (the Robovie simulator needs one)");
  const size_t count = layout.channels.size();
  Films films;
  films.center.resize(count);
  films.half_size.resize(count);
  films.view.resize(count);
  films.body_part.assign(count, -1);
  std::vector<bool> seen(count, false);
  std::map<std::string, int> part_index;
  for (const Taxel& taxel : layout.taxels) {
    const std::string taxel_where = where + " taxel " + std::to_string(taxel.id);
    if (modality >= static_cast<int>(taxel.channels.size()) || taxel.channels[modality] < 0)
      throw Error(taxel_where, "has no piezo channel");
    const size_t channel = static_cast<size_t>(taxel.channels[modality]);
    const auto sides = layout.groups_of(taxel.id, "side");
    const auto parts = layout.groups_of(taxel.id, "body-part");
    if (sides.empty() || (sides[0]->id != "front" && sides[0]->id != "back"))
      throw Error(taxel_where, "is in neither the \"front\" nor the \"back\" side group");
    if (parts.empty()) throw Error(taxel_where, "is in no \"body-part\" group");
    auto [found, added] =
        part_index.try_emplace(parts[0]->id, static_cast<int>(films.body_parts.size()));
    if (added) films.body_parts.push_back(parts[0]->id);
    films.center[channel] = taxel.position;
    films.half_size[channel] = {taxel.size.x * 0.5, taxel.size.y * 0.5};
    films.view[channel] = sides[0]->id == "front" ? View::kFront : View::kBack;
    films.body_part[channel] = found->second;
    seen[channel] = true;
  }
  for (size_t channel = 0; channel < count; ++channel)
    if (!seen[channel])
      throw Error(where + " channel " + layout.channels[channel].name, "belongs to no film");
  return films;
}

MapArea body_area(const Films& films, const std::string& group, View view) {
  const auto part = std::find(films.body_parts.begin(), films.body_parts.end(), group);
  const int index = static_cast<int>(part - films.body_parts.begin());
  MapArea area{{1e300, 1e300}, {-1e300, -1e300}};
  bool any = false;
  for (int64_t film = 0; film < films.count(); ++film) {
    if (films.body_part[film] != index || films.view[film] != view) continue;
    const Point2 c = films.center[film], h = films.half_size[film];
    area.low = {std::min(area.low.x, c.x - h.x), std::min(area.low.y, c.y - h.y)};
    area.high = {std::max(area.high.x, c.x + h.x), std::max(area.high.y, c.y + h.y)};
    any = true;
  }
  if (!any)
    throw Error("body part " + group,
                std::string("has no film on the ") + (view == View::kFront ? "front" : "back"));
  return area;
}

//---- Hands on the skin

void add_contact_load(const Films& films, const Contact& contact, double rate_hz,
                      SampleMatrix& load) {
  if (contact.duration <= 0.0 || contact.force <= 0.0) return;
  const int64_t first =
      std::max<int64_t>(0, static_cast<int64_t>(std::ceil(contact.onset * rate_hz)));
  const int64_t last =
      std::min<int64_t>(load.rows() - 1, static_cast<int64_t>(std::floor(contact.end() * rate_hz)));
  const double patch_area = 4.0 * contact.half_size.x * contact.half_size.y;
  const double two_pi = 2.0 * std::numbers::pi;
  for (int64_t n = first; n <= last; ++n) {
    const double t = static_cast<double>(n) / rate_hz;
    const double envelope =
        contact_envelope(t, contact.onset, contact.duration, contact.rise, contact.fall);
    if (envelope <= 0.0) continue;
    const double elapsed = t - contact.onset;
    // Pumping, squeezing or fingers lifting: the force dips by up to `pulse_depth`.
    const double pulse =
        1.0 - contact.pulse_depth * 0.5 *
                  (1.0 - std::cos(two_pi * contact.pulse_hz * elapsed + contact.phase));
    const double pressure = contact.force * envelope * pulse / patch_area;
    const double swing = std::sin(two_pi * contact.sway_hz * elapsed + contact.phase);
    const double x = contact.center.x + contact.velocity.x * elapsed + contact.sway.x * swing;
    const double y = contact.center.y + contact.velocity.y * elapsed + contact.sway.y * swing;
    for (int64_t film = 0; film < films.count(); ++film) {
      const double dx = std::abs(x - films.center[film].x);
      const double dy = std::abs(y - films.center[film].y);
      const Point2 h = films.half_size[film];
      if (dx >= contact.half_size.x + h.x + kSiliconeBlur ||
          dy >= contact.half_size.y + h.y + kSiliconeBlur)
        continue;
      load(n, film) +=
          static_cast<float>(pressure * soft_overlap(dx, contact.half_size.x, h.x, kSiliconeBlur) *
                             soft_overlap(dy, contact.half_size.y, h.y, kSiliconeBlur));
    }
  }
}

void spread_through_skin(const Films& films, SampleMatrix& load) {
  const int64_t count = films.count();
  // spread(from, to): the share of film `from`'s load that film `to` carries as well.
  Eigen::MatrixXf spread = Eigen::MatrixXf::Identity(count, count);
  for (int64_t from = 0; from < count; ++from)
    for (int64_t to = 0; to < count; ++to) {
      if (to == from || films.view[to] != films.view[from]) continue;
      const double gap = std::hypot(films.center[to].x - films.center[from].x,
                                    films.center[to].y - films.center[from].y);
      spread(from, to) = static_cast<float>(kSpreadShare * std::exp(-gap / kSpreadReach));
    }
  load = load * spread;
}

//---- The robot moving

Eigen::MatrixXf joint_angles(const std::vector<JointMove>& moves, double rate_hz, int64_t samples) {
  Eigen::MatrixXf angles = Eigen::MatrixXf::Zero(samples, kJointCount);
  for (const JointMove& move : moves) {
    if (move.duration <= 0.0) continue;
    const int column = static_cast<int>(move.joint);
    const int64_t first =
        std::max<int64_t>(0, static_cast<int64_t>(std::ceil(move.onset * rate_hz)));
    const int64_t end_index =
        static_cast<int64_t>(std::floor((move.onset + move.duration) * rate_hz));
    // A turn stays where it went: its angle holds to the end of the recording.
    const int64_t last =
        move.shape == JointMove::Shape::kRamp ? samples - 1 : std::min(samples - 1, end_index);
    for (int64_t n = first; n <= last; ++n) {
      const double t = static_cast<double>(n) / rate_hz;
      const double s = std::clamp((t - move.onset) / move.duration, 0.0, 1.0);
      double angle = 0.0;
      switch (move.shape) {
        case JointMove::Shape::kBump:
          angle = move.amplitude * std::pow(std::sin(std::numbers::pi * s), 2);
          break;
        case JointMove::Shape::kRamp:
          // Minimum-jerk profile (Flash & Hogan): 10 s^3 - 15 s^4 + 6 s^5.
          angle = move.amplitude * s * s * s * (10.0 - 15.0 * s + 6.0 * s * s);
          break;
        case JointMove::Shape::kOscillation:
          angle = move.amplitude *
                  std::sin(2.0 * std::numbers::pi * move.frequency_hz * (t - move.onset)) *
                  contact_envelope(t, move.onset, move.duration, 0.3, 0.3);
          break;
      }
      angles(n, column) += static_cast<float>(angle);
    }
  }
  return angles;
}

Robot make_robot(const Films& films, uint64_t seed) {
  Random random(derive_engine(seed, "robovie-robot"));
  const int64_t count = films.count();
  Robot robot;
  robot.gain.resize(count);
  robot.time_constant.resize(count);
  robot.offset.resize(count);
  robot.noise.resize(count);
  robot.coupling.resize(count, kJointCount);
  robot.vibration.resize(count, kJointCount);
  for (int64_t film = 0; film < count; ++film) {
    // Film-to-film spread of sensitivity (silicone thickness, film bonding) and of the
    // amplifier's corner: a constant press is forgotten in 0.15-0.25 s.
    robot.gain[film] = kCountsPerNewton * random.truncated_normal(1.0, 0.15);
    robot.time_constant[film] = random.uniform(0.15, 0.25);
    robot.offset[film] = random.normal(0.0, 8.0);
    robot.noise[film] = random.uniform(8.0, 16.0);
    const std::string& part = films.body_parts[films.body_part[film]];
    for (int joint = 0; joint < kJointCount; ++joint) {
      const auto& weights = joint_weights(static_cast<Joint>(joint));
      const auto found = weights.find(part);
      const double weight = found == weights.end() ? kWholeBodyCoupling : found->second;
      // Bending stretches some films and compresses others: the sign varies film to film.
      robot.coupling(film, joint) =
          static_cast<float>(weight * kBendingLoad * random.normal(0.0, 1.0));
      robot.vibration(film, joint) =
          static_cast<float>(weight * kMotorVibration * random.uniform(0.6, 1.4));
    }
  }
  return robot;
}

void add_joint_load(const Robot& robot, const Eigen::MatrixXf& angles, SampleMatrix& load) {
  load.noalias() += angles * robot.coupling.transpose();
}

//---- The films and their amplifiers

void piezo_output(const Robot& robot, const Eigen::MatrixXf& angles, double rate_hz, Random& noise,
                  SampleMatrix& load) {
  const int64_t samples = load.rows();
  // Joint speeds (rad/s), whose motors and gears shake the shell while they turn.
  Eigen::MatrixXf speed = Eigen::MatrixXf::Zero(samples, kJointCount);
  if (samples > 1)
    speed.bottomRows(samples - 1) =
        ((angles.bottomRows(samples - 1) - angles.topRows(samples - 1)) * rate_hz).cwiseAbs();
  const double dt = 1.0 / rate_hz;
  for (int64_t film = 0; film < load.cols(); ++film) {
    // PVDF film into a charge amplifier: tau dy/dt + y = tau dF/dt, a first-order high-pass
    // of the load; backward Euler: y[n] = a (y[n-1] + F[n] - F[n-1]), a = tau / (tau + dt).
    const double a = robot.time_constant[film] / (robot.time_constant[film] + dt);
    const double gain = robot.gain[film];
    const double offset = robot.offset[film];
    const double floor_variance = robot.noise[film] * robot.noise[film];
    const Eigen::RowVectorXf vibration = robot.vibration.row(film);
    float* column = load.col(film).data();
    double previous_load = 0.0, output = 0.0;
    for (int64_t n = 0; n < samples; ++n) {
      const double current = column[n];
      output = a * (output + current - previous_load);
      previous_load = current;
      const double shaking = vibration.dot(speed.row(n));
      const double sigma = std::sqrt(floor_variance + shaking * shaking);
      column[n] = adc_counts(gain * output + offset + noise.normal(0.0, sigma));
    }
  }
}

}  // namespace tactile::sim::robovie
