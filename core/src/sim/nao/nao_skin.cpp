// The skin of the NAO simulator: hexagonal cells in silicone on the torso (paper 000, Sec 3.1 and
// Table 2). Each cell carries three normal-force sensors under a stiff plate (a load's position
// inside the cell shows in their ratio), an optical proximity sensor (1-200 mm), a 3-axis
// accelerometer (+-2 g, 10 bit) and a temperature sensor. The cell's plate sits on silicone: it
// is a damped mass-spring that rings when hit and is dragged when rubbed.

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "nao_model.h"
#include "tactile/error.h"

namespace tactile::sim::nao {

namespace {

constexpr double kRasterStep = 0.5;   // mm between the points of a side's load raster
constexpr double kPlateScale = 0.92;  // sensing plate / cell outline
// Plate tilt on its silicone bed per N*mm of off-centre load: 1 N at a force sensor (6.7 mm out)
// tilts it by about 1.7 degrees.
constexpr double kTiltPerMoment = 0.0045;
constexpr double kNormalMass = 0.5;     // kg of torso shell a cell's normal load moves
constexpr double kShearMass = 0.6;      // kg, the same for loads along the surface
constexpr double kUpperBodyMass = 2.5;  // kg, NAO's upper body swaying on its joints
// Damping ratio of that sway: NAO's joints turn through high-ratio gearboxes under position
// control, which give way to a push without ringing on (estimate; docs/SIMULATION.md).
constexpr double kSwayDamping = 0.9;
constexpr double kTorsoCurveRadius = 200.0;  // mm, the chest's and back's curve, side to side
constexpr double kMountError = 0.05;         // rad, a cell's tilt and turn off its place
constexpr double kLeverArm = 0.15;           // m from the hips to the middle of the skin
constexpr double kCouplingLength = 25.0;     // mm, decay of vibration through the shell
constexpr double kOtherSideCoupling = 0.02;  // the torso carries a little to the other side
constexpr double kSlipSpeed = 15.0;          // mm/s at which friction reaches its sliding value
constexpr double kTextureStep = 0.25;        // mm between the surface texture's ridges
constexpr double kTextureGain = 3.0;         // texture force per unit friction force
constexpr double kSiliconeCover = 2.0;       // mm of silicone above the proximity sensor
// Optical proximity sensors see a hand beside them as farther than one above them.
constexpr double kLateralWeight = 2.0;
constexpr double kHandWarmth = 3.5;  // degC between a hand's surface and a cell's surface

// An ADC with its scale worked out once (the same levels as sim::quantize, which a hot loop
// of millions of samples cannot afford to recompute).
class Adc {
 public:
  Adc(double low, double high, int bits)
      : low_(low),
        high_(high),
        levels_(std::ldexp(1.0, bits) - 1.0),
        step_((high - low) / levels_) {}
  float operator()(double value) const {
    const double level = std::round((std::clamp(value, low_, high_) - low_) / step_);
    return static_cast<float>(low_ + level * step_);
  }

 private:
  double low_, high_, levels_, step_;
};

// Column of each modality of one cell in the recording.
struct Columns {
  int accel[3];
  int force[3];
  int proximity;
  int temperature;
};

// The fixed properties of one cell: where it is, how its plate resonates, how it is mounted.
struct Cell {
  int side = 0;
  Point2 centre;
  Columns columns{};
  std::array<Point2, 3> sensors{};                       // force sensor positions on the map
  double normal_frequency = 50.0, normal_damping = 0.1;  // Hz, ratio
  double shear_frequency = 20.0, shear_damping = 0.2;
  double facing = 1.0;  // +1: outward normal is the torso's forward axis (front), -1: backward
  Eigen::Matrix3d mount = Eigen::Matrix3d::Identity();  // skin frame -> sensor frame
  Eigen::Vector3d accel_offset = Eigen::Vector3d::Zero();
  Eigen::Vector3d joint_direction = Eigen::Vector3d::UnitZ();
  double joint_gain = 1.0;
  std::array<double, 3> force_offset{}, force_gain{};
  double temperature_offset = 0.0;
  double proximity_gain = 1.0;
};

bool inside(const std::vector<Point2>& polygon, Point2 point) {
  bool result = false;
  for (size_t a = 0, b = polygon.size() - 1; a < polygon.size(); b = a++) {
    const Point2& p = polygon[a];
    const Point2& q = polygon[b];
    if ((p.y > point.y) != (q.y > point.y) &&
        point.x < (q.x - p.x) * (point.y - p.y) / (q.y - p.y) + p.x)
      result = !result;
  }
  return result;
}

// Share of a load at `point` carried by each of three supports: barycentric coordinates,
// clamped to the triangle (outside it the plate tips onto the two nearer supports).
std::array<float, 3> support_shares(const std::array<Point2, 3>& supports, Point2 point) {
  const Point2 &a = supports[0], &b = supports[1], &c = supports[2];
  const double det = (b.y - c.y) * (a.x - c.x) + (c.x - b.x) * (a.y - c.y);
  double l0 = ((b.y - c.y) * (point.x - c.x) + (c.x - b.x) * (point.y - c.y)) / det;
  double l1 = ((c.y - a.y) * (point.x - c.x) + (a.x - c.x) * (point.y - c.y)) / det;
  double l2 = 1.0 - l0 - l1;
  l0 = std::max(0.0, l0);
  l1 = std::max(0.0, l1);
  l2 = std::max(0.0, l2);
  const double sum = l0 + l1 + l2;
  return {static_cast<float>(l0 / sum), static_cast<float>(l1 / sum), static_cast<float>(l2 / sum)};
}

// For each point of one side on a fine grid: the cell under it and its force sensors' shares.
struct LoadRaster {
  Point2 origin;
  int columns = 0, rows = 0;
  std::vector<int> cell;  // index into the cells, -1 where there is no cell
  std::vector<std::array<float, 3>> shares;

  int find(double x, double y) const {
    const int column = static_cast<int>(std::floor((x - origin.x) / kRasterStep));
    const int row = static_cast<int>(std::floor((y - origin.y) / kRasterStep));
    if (column < 0 || row < 0 || column >= columns || row >= rows) return -1;
    return row * columns + column;
  }
};

// Cells are indexed like the layout's taxels.
LoadRaster make_raster(const SkinLayout& layout, const SideArea& side,
                       const std::vector<Cell>& cells) {
  LoadRaster raster;
  raster.origin = side.low;
  raster.columns = static_cast<int>(std::ceil((side.high.x - side.low.x) / kRasterStep));
  raster.rows = static_cast<int>(std::ceil((side.high.y - side.low.y) / kRasterStep));
  raster.cell.assign(static_cast<size_t>(raster.columns) * raster.rows, -1);
  raster.shares.resize(raster.cell.size());
  for (int taxel : side.cells) {
    // The sensing plate is a little smaller than the cell: a load on the silicone seam
    // between plates goes to the shell.
    const Cell& cell = cells[taxel];
    std::vector<Point2> outline = taxel_outline(layout.taxels[taxel]);
    for (Point2& corner : outline)
      corner = {cell.centre.x + kPlateScale * (corner.x - cell.centre.x),
                cell.centre.y + kPlateScale * (corner.y - cell.centre.y)};
    double low_x = 1e300, high_x = -1e300, low_y = 1e300, high_y = -1e300;
    for (const Point2& p : outline) {
      low_x = std::min(low_x, p.x), high_x = std::max(high_x, p.x);
      low_y = std::min(low_y, p.y), high_y = std::max(high_y, p.y);
    }
    for (int row = std::max(0, static_cast<int>((low_y - raster.origin.y) / kRasterStep));
         row <
         std::min(raster.rows, static_cast<int>((high_y - raster.origin.y) / kRasterStep) + 1);
         ++row)
      for (int column = std::max(0, static_cast<int>((low_x - raster.origin.x) / kRasterStep));
           column <
           std::min(raster.columns, static_cast<int>((high_x - raster.origin.x) / kRasterStep) + 1);
           ++column) {
        const Point2 point{raster.origin.x + (column + 0.5) * kRasterStep,
                           raster.origin.y + (row + 0.5) * kRasterStep};
        if (!inside(outline, point)) continue;
        const size_t index = static_cast<size_t>(row) * raster.columns + column;
        raster.cell[index] = taxel;
        raster.shares[index] = support_shares(cell.sensors, point);
      }
  }
  return raster;
}

// Points of a unit disk, each standing for an equal area, weighted by a paraboloid pressure
// (Hertz-like contact of a soft body part: highest in the middle, zero at the rim).
struct FootprintPoint {
  double u, v, weight;
};

std::vector<FootprintPoint> footprint_points(double semi_major) {
  const int rings = std::max(2, static_cast<int>(std::ceil(semi_major / 3.5)));
  std::vector<FootprintPoint> points;
  double total = 0.0;
  for (int ring = 0; ring <= rings; ++ring) {
    const double radius = ring / (rings + 0.5);
    const int count = ring == 0 ? 1 : 6 * ring;
    for (int k = 0; k < count; ++k) {
      const double angle = 2.0 * std::numbers::pi * (k + 0.5 * (ring % 2)) / count;
      const double weight = 1.0 - radius * radius;
      points.push_back({radius * std::cos(angle), radius * std::sin(angle), weight});
      total += weight;
    }
  }
  for (FootprintPoint& point : points) point.weight /= total;
  return points;
}

// The skin's surface texture (3D-printed silicone): a fixed random height profile along any
// path. A part sliding over it feels the profile averaged over its contact width.
class SurfaceTexture {
 public:
  explicit SurfaceTexture(Random& random) : prefix_(kLength + 1, 0.0) {
    for (int k = 0; k < kLength; ++k) prefix_[k + 1] = prefix_[k] + random.normal();
  }
  double average(double position, double width) const {
    const int count = std::max(1, static_cast<int>(std::lround(width / kTextureStep)));
    int64_t start = static_cast<int64_t>(std::floor(position / kTextureStep)) % kLength;
    if (start < 0) start += kLength;
    double sum = 0.0;
    for (int remaining = count; remaining > 0;) {
      const int take = static_cast<int>(std::min<int64_t>(remaining, kLength - start));
      sum += prefix_[start + take] - prefix_[start];
      remaining -= take;
      start = 0;
    }
    return sum / count;
  }

 private:
  static constexpr int kLength = 8192;
  std::vector<double> prefix_;
};

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// What the hand does to the cells, per sample: loads on the force sensors, tangential load on
// the plates (friction and texture), normal texture load, and the distance to the hand.
struct CellLoads {
  RowMatrix sensor_force;    // samples x (cells * 3), N
  RowMatrix shear;           // samples x (cells * 2), N along map x and y
  RowMatrix normal_texture;  // samples x cells, N
  RowMatrix distance;        // samples x cells, mm
};

// Presses, drags and hovers one hand part over its side's cells.
void apply_part(const HandPart& part, const std::vector<Cell>& cells, const SideArea& side,
                const LoadRaster& raster, const SurfaceTexture& texture, double texture_start,
                double rate_hz, CellLoads& loads, std::vector<double>& share) {
  const int64_t samples = loads.distance.rows();
  const std::vector<FootprintPoint> points = footprint_points(part.semi_major);
  const Point2 major{std::sin(part.angle), -std::cos(part.angle)};  // as the hand's `along`
  const Point2 minor{std::cos(part.angle), std::sin(part.angle)};
  double path = texture_start;
  const int64_t count = static_cast<int64_t>(part.x.size());
  for (int64_t k = 0; k < count; ++k) {
    const int64_t sample = part.first_sample + k;
    if (sample < 0 || sample >= samples) continue;
    const double x = part.x[k], y = part.y[k];
    // Proximity: the part's height, and how far beside the cell its footprint lies.
    for (int index : side.cells) {
      const double dx = cells[index].centre.x - x, dy = cells[index].centre.y - y;
      const double along = (dx * major.x + dy * major.y) / part.semi_major;
      const double across = (dx * minor.x + dy * minor.y) / part.semi_minor;
      const double radius = std::sqrt(along * along + across * across);
      const double beside =
          radius > 1.0 ? std::sqrt(dx * dx + dy * dy) * (1.0 - 1.0 / radius) : 0.0;
      const double above = part.height[k] + kSiliconeCover;
      const double distance =
          std::sqrt(above * above + kLateralWeight * kLateralWeight * beside * beside);
      double& nearest = loads.distance(sample, index);
      nearest = std::min(nearest, distance);
    }
    const double force = part.force[k];
    if (force <= 0.0) continue;
    const int64_t before = std::max<int64_t>(0, k - 1), after = std::min(count - 1, k + 1);
    const double span = static_cast<double>(std::max<int64_t>(1, after - before)) / rate_hz;
    const double velocity_x = (part.x[after] - part.x[before]) / span;
    const double velocity_y = (part.y[after] - part.y[before]) / span;
    const double speed = std::hypot(velocity_x, velocity_y);
    path += speed / rate_hz;
    for (int index : side.cells) share[index] = 0.0;
    for (const FootprintPoint& point : points) {
      const double u = point.u * part.semi_major, v = point.v * part.semi_minor;
      const int spot = raster.find(x + u * major.x + v * minor.x, y + u * major.y + v * minor.y);
      if (spot < 0 || raster.cell[spot] < 0) continue;  // on the robot between or beside cells
      const int cell = raster.cell[spot];
      const double load = force * point.weight;
      share[cell] += load;
      for (int sensor = 0; sensor < 3; ++sensor)
        loads.sensor_force(sample, 3 * cell + sensor) += load * raster.shares[spot][sensor];
    }
    if (speed <= 0.0) continue;
    // Sliding friction drags the plates along the motion; the texture's ridges shake them.
    const double friction = part.friction * force * std::tanh(speed / kSlipSpeed);
    const double ridges = kTextureGain * friction * texture.average(path, part.texture_width);
    for (int index : side.cells) {
      if (share[index] <= 0.0) continue;
      const double fraction = share[index] / force;
      loads.shear(sample, 2 * index) += fraction * (friction + ridges) * velocity_x / speed;
      loads.shear(sample, 2 * index + 1) += fraction * (friction + ridges) * velocity_y / speed;
      loads.normal_texture(sample, index) += fraction * 0.7 * ridges;
    }
  }
}

// A damped mass-spring driven by force per unit mass, discretised exactly with the input held
// over each sample; step() returns the mass's acceleration.
class Resonator {
 public:
  Resonator(double frequency_hz, double damping, double rate_hz) {
    const double dt = 1.0 / rate_hz;
    omega_ = 2.0 * std::numbers::pi * frequency_hz;
    damping_ = damping;
    const double sigma = -damping * omega_;
    const double damped = omega_ * std::sqrt(1.0 - damping * damping);
    const double decay = std::exp(sigma * dt), cosine = std::cos(damped * dt);
    const double sine = std::sin(damped * dt) / damped;
    // exp(A dt) = e^(sigma dt) [cos(wd dt) I + sin(wd dt)/wd (A - sigma I)],
    // A = [[0, 1], [-w^2, -2 z w]]; input matrix A^-1 (exp(A dt) - I) [0, 1]^T.
    phi_[0] = decay * (cosine - sigma * sine);
    phi_[1] = decay * sine;
    phi_[2] = -decay * sine * omega_ * omega_;
    phi_[3] = decay * (cosine - damping * omega_ * sine);
    gamma_[0] = (1.0 - phi_[0]) / (omega_ * omega_);
    gamma_[1] = phi_[1];
  }
  double position() const { return position_; }
  double step(double input) {
    const double acceleration =
        input - 2.0 * damping_ * omega_ * velocity_ - omega_ * omega_ * position_;
    const double position = phi_[0] * position_ + phi_[1] * velocity_ + gamma_[0] * input;
    velocity_ = phi_[2] * position_ + phi_[3] * velocity_ + gamma_[1] * input;
    position_ = position;
    return acceleration;
  }

 private:
  double omega_ = 0.0, damping_ = 0.0;
  double phi_[4] = {}, gamma_[2] = {};
  double position_ = 0.0, velocity_ = 0.0;
};

std::vector<Cell> make_cells(const SkinLayout& layout, const std::vector<SideArea>& sides,
                             Random& hardware) {
  static const char* const kModalities[] = {"ax", "ay", "az", "f1", "f2", "f3", "prox", "temp"};
  int slot[8];
  for (int m = 0; m < 8; ++m) {
    slot[m] = layout.modality_index(kModalities[m]);
    if (slot[m] < 0)
      throw Error("layout " + layout.id,
                  std::string("the nao simulator needs modality \"") + kModalities[m] + "\"");
  }
  std::vector<Cell> cells(layout.taxels.size());
  for (size_t index = 0; index < cells.size(); ++index) {
    const Taxel& taxel = layout.taxels[index];
    Cell& cell = cells[index];
    int column[8];
    for (int m = 0; m < 8; ++m) {
      column[m] = slot[m] < static_cast<int>(taxel.channels.size()) ? taxel.channels[slot[m]] : -1;
      if (column[m] < 0)
        throw Error("layout " + layout.id + " taxel " + std::to_string(taxel.id),
                    std::string("no \"") + kModalities[m] + "\" channel");
    }
    cell.columns = {
        {column[0], column[1], column[2]}, {column[3], column[4], column[5]}, column[6], column[7]};
    cell.centre = taxel.position;
    cell.side = -1;
    for (size_t side = 0; side < sides.size(); ++side)
      if (std::find(sides[side].cells.begin(), sides[side].cells.end(), static_cast<int>(index)) !=
          sides[side].cells.end())
        cell.side = static_cast<int>(side);
    cell.facing = cell.side >= 0 && sides[cell.side].id == "back" ? -1.0 : 1.0;
    // Force sensors under the plate, halfway out to the flat sides: f1 top, f2 and f3 below.
    const double radius = 0.55 * 0.5 * std::min(taxel.size.x, taxel.size.y);
    for (int sensor = 0; sensor < 3; ++sensor) {
      const double angle = -0.5 * std::numbers::pi + sensor * 2.0 * std::numbers::pi / 3.0;
      cell.sensors[sensor] = {cell.centre.x + radius * std::cos(angle),
                              cell.centre.y + radius * std::sin(angle)};
    }
    cell.normal_frequency = hardware.uniform(35.0, 75.0);
    cell.normal_damping = hardware.uniform(0.08, 0.15);
    cell.shear_frequency = hardware.uniform(15.0, 30.0);
    cell.shear_damping = hardware.uniform(0.15, 0.3);
    // Cells follow the torso's curve around its vertical axis: a cell sits tilted by its
    // distance from the middle of its side over the curve's radius, give or take the few
    // degrees of hand assembly.
    const Point2 middle = cell.side >= 0 ? sides[cell.side].centre : cell.centre;
    const double tilt_x = hardware.uniform(-kMountError, kMountError);
    const double tilt_y = hardware.uniform(-kMountError, kMountError) +
                          (cell.centre.x - middle.x) / kTorsoCurveRadius;
    const double turn = hardware.uniform(-kMountError, kMountError);
    const Eigen::Matrix3d placed = (Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitZ()) *
                                    Eigen::AngleAxisd(tilt_y, Eigen::Vector3d::UnitY()) *
                                    Eigen::AngleAxisd(tilt_x, Eigen::Vector3d::UnitX()))
                                       .toRotationMatrix();
    cell.mount = placed.transpose();
    for (int axis = 0; axis < 3; ++axis) cell.accel_offset[axis] = hardware.normal(0.0, 0.02);
    cell.joint_direction =
        Eigen::Vector3d(hardware.normal(0.0, 0.3), hardware.normal(0.0, 0.3), 1.0).normalized();
    cell.joint_gain = hardware.uniform(0.6, 1.4);
    for (int sensor = 0; sensor < 3; ++sensor) {
      cell.force_offset[sensor] = hardware.uniform(0.01, 0.04);
      cell.force_gain[sensor] = hardware.uniform(0.9, 1.1);
    }
    cell.temperature_offset = hardware.normal(0.0, 0.3);
    cell.proximity_gain = hardware.uniform(0.95, 1.05);
  }
  return cells;
}

}  // namespace

void render_skin(const SkinLayout& layout, const std::vector<SideArea>& sides,
                 const std::vector<Gesture>& gestures, const BodyMotion& body, double rate_hz,
                 Random& hardware, Random& noise, Eigen::Ref<Eigen::MatrixXf> samples) {
  const int64_t count = samples.rows();
  const std::vector<Cell> cells = make_cells(layout, sides, hardware);
  const SurfaceTexture texture(hardware);
  const Eigen::Index cell_count = static_cast<Eigen::Index>(cells.size());
  std::vector<LoadRaster> rasters;
  for (const SideArea& side : sides) rasters.push_back(make_raster(layout, side, cells));

  CellLoads loads;
  loads.sensor_force = RowMatrix::Zero(count, 3 * cell_count);
  loads.shear = RowMatrix::Zero(count, 2 * cell_count);
  loads.normal_texture = RowMatrix::Zero(count, cell_count);
  loads.distance = RowMatrix::Constant(count, cell_count, std::numeric_limits<double>::infinity());
  std::vector<double> share(cells.size(), 0.0);
  for (const Gesture& gesture : gestures)
    for (const HandPart& part : gesture.parts)
      apply_part(part, cells, sides[gesture.side], rasters[gesture.side], texture,
                 noise.uniform(0.0, 2000.0), rate_hz, loads, share);

  // Vibration travels through the torso shell: nearby plates shake with a touched one.
  Eigen::MatrixXd coupling(cell_count, cell_count);
  for (Eigen::Index a = 0; a < cell_count; ++a)
    for (Eigen::Index b = 0; b < cell_count; ++b) {
      const double distance =
          std::hypot(cells[a].centre.x - cells[b].centre.x, cells[a].centre.y - cells[b].centre.y);
      coupling(a, b) = cells[a].side == cells[b].side ? std::exp(-distance / kCouplingLength)
                                                      : kOtherSideCoupling;
    }
  Eigen::MatrixXd normal(count, cell_count), shear_x(count, cell_count), shear_y(count, cell_count);
  for (Eigen::Index c = 0; c < cell_count; ++c) {
    normal.col(c) = loads.sensor_force.col(3 * c) + loads.sensor_force.col(3 * c + 1) +
                    loads.sensor_force.col(3 * c + 2) + loads.normal_texture.col(c);
    shear_x.col(c) = loads.shear.col(2 * c);
    shear_y.col(c) = loads.shear.col(2 * c + 1);
  }
  const Eigen::MatrixXd coupled_normal = normal * coupling.transpose();
  const Eigen::MatrixXd coupled_x = shear_x * coupling.transpose();
  const Eigen::MatrixXd coupled_y = shear_y * coupling.transpose();

  // The sitting robot gives way under the hand: its servo-held upper body sways like a damped
  // mass-spring (a few Hz), and leans a little, so every cell feels a hand's push or rub.
  Eigen::MatrixXd torso = body.specific_force;
  {
    Resonator sway[3] = {Resonator(hardware.uniform(3.0, 6.0), kSwayDamping, rate_hz),
                         Resonator(hardware.uniform(5.0, 9.0), kSwayDamping, rate_hz),
                         Resonator(hardware.uniform(3.0, 6.0), kSwayDamping, rate_hz)};
    Eigen::VectorXd facing(cell_count);
    for (Eigen::Index c = 0; c < cell_count; ++c) facing[c] = cells[c].facing;
    // Net force of the hand on the torso (N), torso frame.
    const Eigen::VectorXd push_x = shear_x * facing;
    const Eigen::VectorXd push_y = shear_y.rowwise().sum();
    const Eigen::VectorXd push_z = -(normal * facing);
    for (int64_t s = 0; s < count; ++s) {
      const Eigen::Vector3d push(push_x[s], push_y[s], push_z[s]);
      Eigen::Vector3d acceleration, displacement;
      for (int axis = 0; axis < 3; ++axis) {
        acceleration[axis] = sway[axis].step(push[axis] / kUpperBodyMass) / kGravity;
        displacement[axis] = sway[axis].position();
      }
      // Moving forward or sideways at shoulder height tips the torso about the hips.
      const Eigen::Vector3d tilt(-displacement.z() / kLeverArm, 0.0, displacement.x() / kLeverArm);
      const Eigen::Vector3d resting = torso.row(s).transpose();
      torso.row(s) = (resting + tilt.cross(resting) + acceleration).transpose();
    }
  }

  // Slow changes of this session: room and robot temperature, force sensor creep.
  const double ambient = noise.uniform(28.0, 32.0);
  const double warming = noise.normal(0.0, 0.15);  // degC over the recording
  const double duration = std::max(1.0, static_cast<double>(count) / rate_hz);
  const double dt = 1.0 / rate_hz;
  const Adc accelerometer(-2.0, 2.0, 10), force_sensor(0.0, 3.0, 12);
  const Adc proximity_sensor(1.0, 200.0, 16), thermometer(-40.0, 150.0, 14);
  const double warming_rate = 1.0 - std::exp(-dt / 20.0), cooling_rate = 1.0 - std::exp(-dt / 40.0);
  for (Eigen::Index c = 0; c < cell_count; ++c) {
    const Cell& cell = cells[c];
    // Accelerometer: plate motion, body motion and joint vibration, seen through the mounting.
    Resonator normal_plate(cell.normal_frequency, cell.normal_damping, rate_hz);
    Resonator shear_x_plate(cell.shear_frequency, cell.shear_damping, rate_hz);
    Resonator shear_y_plate(cell.shear_frequency, cell.shear_damping, rate_hz);
    for (int64_t s = 0; s < count; ++s) {
      // Pressing moves the plate inward, against its outward normal (+z).
      const Eigen::Vector3d plate(shear_x_plate.step(coupled_x(s, c) / kShearMass),
                                  shear_y_plate.step(coupled_y(s, c) / kShearMass),
                                  normal_plate.step(-coupled_normal(s, c) / kNormalMass));
      const Eigen::Vector3d gravity(cell.facing * torso(s, 0), torso(s, 1),
                                    cell.facing * torso(s, 2));
      // A load off the plate's middle sinks that edge into the silicone: the plate tilts and
      // the accelerometer sees gravity turn (rotation about the axis normal x lever).
      double moment_x = 0.0, moment_y = 0.0;
      for (int sensor = 0; sensor < 3; ++sensor) {
        const double load = loads.sensor_force(s, 3 * c + sensor);
        moment_x += load * (cell.sensors[sensor].x - cell.centre.x);
        moment_y += load * (cell.sensors[sensor].y - cell.centre.y);
      }
      const Eigen::Vector3d tilt(-kTiltPerMoment * moment_y, kTiltPerMoment * moment_x, 0.0);
      const Eigen::Vector3d skin = plate / kGravity + gravity + tilt.cross(gravity) +
                                   body.joint_vibration(s) * cell.joint_gain * cell.joint_direction;
      const Eigen::Vector3d sensed = cell.mount * skin + cell.accel_offset;
      for (int axis = 0; axis < 3; ++axis)
        samples(s, cell.columns.accel[axis]) =
            accelerometer(sensed[axis] + noise.normal(0.0, 0.006));
    }
    // Force sensors: 0-3 N, 12 bit, with a rest offset from the silicone's preload and creep.
    for (int sensor = 0; sensor < 3; ++sensor) {
      const double creep = noise.normal(0.0, 0.01) / duration;  // N per second
      for (int64_t s = 0; s < count; ++s) {
        const double value = cell.force_gain[sensor] * loads.sensor_force(s, 3 * c + sensor) +
                             cell.force_offset[sensor] + creep * static_cast<double>(s) * dt +
                             noise.normal(0.0, 0.0025);
        samples(s, cell.columns.force[sensor]) = force_sensor(value);
      }
    }
    // Proximity: 1-200 mm; with nothing in range the sensor sits at its 200 mm end.
    for (int64_t s = 0; s < count; ++s) {
      const double distance = loads.distance(s, c) * cell.proximity_gain;
      samples(s, cell.columns.proximity) =
          distance > 220.0 ? proximity_sensor(200.0)
                           : proximity_sensor(distance + noise.normal(0.0, 0.3 + 0.01 * distance));
    }
    // Temperature: a hand warms the cell slowly (tens of seconds); it cools slower still.
    double warmth = 0.0;
    for (int64_t s = 0; s < count; ++s) {
      const double pressed = loads.sensor_force(s, 3 * c) + loads.sensor_force(s, 3 * c + 1) +
                             loads.sensor_force(s, 3 * c + 2);
      const double contact = std::clamp(pressed / 0.3, 0.0, 1.0);
      warmth += (contact * kHandWarmth - warmth) * (contact > 0.0 ? warming_rate : cooling_rate);
      const double value = ambient + cell.temperature_offset +
                           warming * static_cast<double>(s) * dt / duration + warmth +
                           noise.normal(0.0, 0.01);
      samples(s, cell.columns.temperature) = thermometer(value);
    }
  }
}

}  // namespace tactile::sim::nao
