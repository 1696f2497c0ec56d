#pragma once
// Feature set "tsa_event" (paper 001, spec §2.5-2.11): per single-touch event on one 4x4
// sheet, the time, the direction class of Fig. 8, the spread area (eq. 8) and the sheet's
// location code; optionally the intra-frame statistics D1-D4 (eqs. 5-6).

#include <array>
#include <memory>
#include <vector>

#include "tactile/features/feature_extractor.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/parameters.h"

namespace tactile {

// One active contact of a frame: its pad position in pitch units (x = column to the right,
// y = row downwards) and its value above baseline.
struct TsaContact {
  Point2 position;
  double value = 0.0;
};
using TsaFrame = std::vector<TsaContact>;  // the active contacts of one frame (K_n)

// TSA eq. (7): c_n = (1/m_n) Σ p over the active contacts, unweighted; (0, 0) when empty.
Point2 tsa_centroid(const TsaFrame& frame);

enum class TsaAreaMode {
  kDistanceSum,  // text reading of eq. (8): Σ_n Σ_p ||p - c_n|| (spec default)
  kEq8Literal,   // eq. (8) as typeset: Σ_n sqrt(Σ_p ||p - c_n||²)
  kCount,        // Table 3: Σ_n m_n, the number of triggered points
};
// TSA eq. (8) over the frames of an event; empty frames add nothing.
double tsa_area(const std::vector<TsaFrame>& frames, TsaAreaMode mode);

// D1 mean value, D2 max value, D3 sample std of the values, D4 max distance of an active
// pad from the sheet's centre (spec §2.5); all 0 for an empty frame.
std::array<double, 4> tsa_frame_descriptors(const TsaFrame& frame, Point2 sheet_centre);
// TSA eqs. (5)-(6) over the non-empty frames: [mean D1..D4, sample std D1..D4].
std::array<double, 8> tsa_descriptor_statistics(const std::vector<TsaFrame>& frames,
                                                Point2 sheet_centre);

struct TsaPathShape {
  double signed_area = 0.0;       // shoelace over the closed path; > 0 = clockwise (y down)
  double length = 0.0;            // Σ |c_{k+1} - c_k|
  double net_displacement = 0.0;  // |c_N - c_1|
  double angle_degrees = 0.0;     // atan2(-Δy, Δx) in [0, 360), 0 = rightwards
};
TsaPathShape tsa_path_shape(const std::vector<Point2>& path);

struct TsaDirectionOptions {
  double minimum_area = 0.5;          // A_min, pitch²
  double rotation_ratio = 0.5;        // ρ: a rotation returns close to where it began
  double minimum_displacement = 0.5;  // d_min, pitch
};
// Spec §2.10: 0 none, 1 clockwise, 2 counter-clockwise, 3 left->right, 4 right->left,
// 5 up->down, 6 down->up, 7 upper-left->lower-right, 8 lower-right->upper-left,
// 9 lower-left->upper-right, 10 upper-right->lower-left.
int tsa_direction_code(const std::vector<Point2>& path, const TsaDirectionOptions& options = {});
constexpr int kTsaDirectionCodes = 11;

// Parameters: tsa_features (BASIC | EXTENDED), area_mode (TEXT | EQ8_LITERAL | COUNT),
// direction (code | onehot), location (code | onehot), direction_min_area,
// direction_ratio, direction_min_displacement, and the preprocessing keys of
// dsp::tsa_preprocess_keys(). Throws tactile::Error naming a bad one.
std::unique_ptr<FeatureExtractor> make_tsa_event_extractor(const Parameters& parameters);

}  // namespace tactile
