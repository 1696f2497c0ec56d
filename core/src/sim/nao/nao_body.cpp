// The robot under the skin (paper 000, Sec 4.3 "NAO in motion"): sitting still, walking toward
// and backward, or sitting down and standing up continuously. What the cells' accelerometers
// feel of it: gravity turning with the torso, the torso's own acceleration, heel strikes, and
// the vibration of the joints' gears while they move.

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "nao_model.h"
#include "tactile/error.h"

namespace tactile::sim::nao {

namespace {

// The torso's path: position (m) in a world frame with the robot's axes at rest (x: left,
// y: down, z: forward), its pitch (forward lean) and roll (sideways sway) in rad, and how busy
// its joints are (0 still .. 1 moving).
struct TorsoPath {
  std::vector<double> left, down, forward, pitch, roll, joint_activity;
  std::vector<double> shock;  // m/s^2 upward, short impacts (heel strikes)
  explicit TorsoPath(int64_t samples)
      : left(samples),
        down(samples),
        forward(samples),
        pitch(samples),
        roll(samples),
        joint_activity(samples),
        shock(samples) {}
};

// The torso's path is smooth: each transition starts from the height the previous one reached
// and every motion starts and ends at rest (a jump in position or velocity between two samples
// reads as a 1-2 g spike, which no robot makes and which swamps every variance a touch adds).
void sit_and_stand(TorsoPath& path, double rate_hz, Random& random) {
  const int64_t samples = static_cast<int64_t>(path.pitch.size());
  double t = random.uniform(0.0, 1.5);
  bool standing = random.chance(0.5);
  double height = standing ? random.uniform(0.12, 0.18) : 0.0;  // m above the seated torso
  // Hold the starting posture until the first transition.
  for (int64_t s = 0; s < samples; ++s) path.down[s] = -height;
  while (t * rate_hz < static_cast<double>(samples)) {
    const double duration = random.uniform(2.0, 3.0), lean = random.uniform(0.35, 0.6);
    const double target = standing ? 0.0 : random.uniform(0.12, 0.18);
    const double travel = random.uniform(0.03, 0.06), hold = random.uniform(0.5, 1.5);
    const int64_t first = static_cast<int64_t>(std::ceil(t * rate_hz));
    for (int64_t s = std::max<int64_t>(0, first); s < samples; ++s) {
      const double p = std::clamp((static_cast<double>(s) / rate_hz - t) / duration, 0.0, 1.0);
      path.down[s] = -(height + (target - height) * minimum_jerk(p));
      if (p < 1.0) {
        // The torso leans forward and the hips move forward while rising or sitting, starting
        // and ending at rest (a bump of sin^2: the velocity is zero at both ends).
        const double bump = std::pow(std::sin(kPi * p), 2);
        path.pitch[s] = lean * bump;
        path.forward[s] = travel * bump;
        path.joint_activity[s] = bump;
      }
    }
    height = target;
    standing = !standing;
    t += duration + hold;
  }
}

void walk(TorsoPath& path, double rate_hz, Random& random) {
  const int64_t samples = static_cast<int64_t>(path.pitch.size());
  const double step_frequency = random.uniform(1.6, 2.1);  // steps per second
  const double sway = random.uniform(0.01, 0.02), bounce = random.uniform(0.003, 0.006);
  const double roll = random.uniform(0.03, 0.06);
  const double strike = random.uniform(0.2, 0.6), strike_frequency = random.uniform(25.0, 40.0);
  double t = random.uniform(0.0, 1.0), position = 0.0, direction = 1.0;
  int64_t s = 0;
  for (; s < samples && static_cast<double>(s) / rate_hz < t; ++s) path.forward[s] = position;
  while (s < samples) {
    const double walking = random.uniform(4.0, 7.0), stop = random.uniform(0.5, 1.0);
    const double speed = random.uniform(0.08, 0.12) * direction;
    const double start = t;
    for (; s < samples && static_cast<double>(s) / rate_hz < start + walking; ++s) {
      const double time = static_cast<double>(s) / rate_hz - start;
      // Start and stop smoothly over 0.4 s (a linear ramp would jump the sway's velocity).
      const double ramp =
          minimum_jerk(std::clamp(std::min(time / 0.4, (walking - time) / 0.4), 0.0, 1.0));
      const double stride = 2.0 * kPi * step_frequency * time;
      position += ramp * speed / rate_hz;
      path.forward[s] = position;
      path.left[s] = ramp * sway * std::sin(0.5 * stride);
      path.down[s] = -ramp * bounce * std::sin(stride);
      path.roll[s] = ramp * roll * std::sin(0.5 * stride);
      path.pitch[s] = ramp * 0.02 * std::sin(stride);
      path.joint_activity[s] = ramp;
      // A heel strike at the start of every step rings through the robot.
      const double since_step = std::fmod(time, 1.0 / step_frequency);
      path.shock[s] = ramp * strike * std::exp(-since_step / 0.03) *
                      std::sin(2.0 * kPi * strike_frequency * since_step);
    }
    for (; s < samples && static_cast<double>(s) / rate_hz < start + walking + stop; ++s)
      path.forward[s] = position;
    t = start + walking + stop;
    direction = -direction;  // toward, then backward
  }
}

}  // namespace

BodyMotion simulate_body_motion(const std::string& motion, int64_t samples, double rate_hz,
                                Random& random) {
  BodyMotion body;
  body.motion = motion;
  body.specific_force = Eigen::MatrixXd::Zero(samples, 3);
  body.joint_vibration = Eigen::VectorXd::Zero(samples);
  TorsoPath path(samples);
  // Sitting posture of this session.
  const double base_pitch = random.uniform(-0.05, 0.12), base_roll = random.uniform(-0.03, 0.03);
  if (motion == "sit-stand")
    sit_and_stand(path, rate_hz, random);
  else if (motion == "walking")
    walk(path, rate_hz, random);
  else if (motion != "none")
    throw Error("nao motion", "unknown body motion \"" + motion + "\" (none, walking, sit-stand)");
  // The gears of the moving joints buzz at their mesh frequency and its neighbours.
  const double mesh = random.uniform(40.0, 60.0), buzz = random.uniform(0.004, 0.008);
  const double mesh_phase = random.uniform(0.0, 2.0 * kPi);
  for (int64_t s = 0; s < samples; ++s) {
    // Linear acceleration by second differences of the path (m/s^2); the first and last
    // samples take their neighbour's.
    const int64_t c = std::clamp<int64_t>(s, 1, std::max<int64_t>(1, samples - 2));
    auto second_difference = [&](const std::vector<double>& x) {
      return samples < 3 ? 0.0 : (x[c + 1] - 2.0 * x[c] + x[c - 1]) * rate_hz * rate_hz;
    };
    const Eigen::Vector3d acceleration(second_difference(path.left),
                                       second_difference(path.down) - path.shock[s],
                                       second_difference(path.forward));
    // An accelerometer reads acceleration minus gravity: 1 g upward (-y) at rest.
    const Eigen::Vector3d world = acceleration / kGravity + Eigen::Vector3d(0.0, -1.0, 0.0);
    // Leaning forward turns the forward axis (z) toward down (y): a rotation about x.
    const Eigen::Matrix3d torso =
        (Eigen::AngleAxisd(-(base_pitch + path.pitch[s]), Eigen::Vector3d::UnitX()) *
         Eigen::AngleAxisd(base_roll + path.roll[s], Eigen::Vector3d::UnitZ()))
            .toRotationMatrix();
    body.specific_force.row(s) = (torso.transpose() * world).transpose();
    const double t = static_cast<double>(s) / rate_hz;
    const double activity = path.joint_activity[s];
    body.joint_vibration(s) = activity * (buzz * std::sin(2.0 * kPi * mesh * t + mesh_phase) +
                                          0.5 * buzz * std::sin(2.0 * kPi * 1.7 * mesh * t) +
                                          random.normal(0.0, 0.3 * buzz));
  }
  return body;
}

}  // namespace tactile::sim::nao
