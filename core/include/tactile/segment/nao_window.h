#pragma once
// The NAO skin as Kaboli et al. and their adapted baselines see it (spec §1): cells grouped
// into body parts (layout groups of kind "side"), each cell's columns in the recording, the
// action window of a labelled segment with the dynamic cell selection ζ of eq. (1), and the
// force contact flags of §1.10 that the baselines share.

#include <Eigen/Core>
#include <array>
#include <span>
#include <string>
#include <vector>

#include "tactile/io/recording.h"
#include "tactile/labelstore/label.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/parameters.h"

namespace tactile {

// The contact distance of eq. (1) (spec §1.2), in mm.
constexpr double kDefaultContactDistanceMm = 50.0;

// Columns of one cell in its stream.
struct CellColumns {
  int64_t taxel = 0;
  std::array<int, 3> acceleration{};  // ax, ay, az
  std::vector<int> force;             // f1..fN in the layout's modality order
  int proximity = 0;
};

struct BodyPart {
  std::string id;                  // group id, e.g. "front"
  std::vector<CellColumns> cells;  // in the group's cell order
};

struct NaoSkin {
  const Stream* stream = nullptr;    // the stream holding the cells' channels
  std::vector<BodyPart> body_parts;  // groups of kind "side", in layout order
};

// Finds every cell's columns. Throws tactile::Error naming the layout when it lacks side groups
// or the ax/ay/az/f*/prox modalities, or the recording when no stream holds a cell's channel.
NaoSkin locate_nao_skin(const Recording& recording, const SkinLayout& layout);

// Kaboli et al. eq. (1): ζ_c = 1 if min_t d^c(t) < d_contact (strict; a NaN reading is no contact).
bool cell_in_contact(std::span<const float> proximity_mm, double contact_mm);

// One labelled segment on one body part: its samples [first, first + count) and ζ per cell.
struct ContactWindow {
  int body_part = -1;  // index into NaoSkin::body_parts
  int64_t first = 0;
  int64_t count = 0;
  std::vector<char> contact;  // ζ_c, one per cell of the body part
  int64_t contacted_cells = 0;
  std::string skip_reason;  // non-empty: this segment gives no row, and why
};

// The body part of a segment is its region ("front", "back", any side group) or, for region
// "all", the side with more contacted cells (the first in layout order on a tie). Skips an
// unknown region, a window of fewer than `minimum_samples`, a non-finite proximity reading
// and a window where no cell is in contact ("no cell in contact").
ContactWindow contact_window(const NaoSkin& skin, const Label& segment, double contact_mm,
                             int64_t minimum_samples);

// Names the first non-finite sample of the given columns in the window ("" when all finite).
std::string find_non_finite(const Stream& stream, std::span<const int> columns, int64_t first,
                            int64_t count);

// One column of the window as doubles.
Eigen::VectorXd window_column(const Stream& stream, int column, int64_t first, int64_t count);

// The force elements e = (cell, sensor) of the window, cell ascending then sensor 1..N_f, as a
// T x E matrix (one contiguous column per element). All cells of the body part, as printed in
// spec §1.10, or only those with ζ = 1.
Eigen::MatrixXd force_elements(const NaoSkin& skin, const ContactWindow& window,
                               bool contacted_only);

// Spec §1.10: b_e(t) = 1 if F_e(t) >= f_thresh else 0, as a T x E array of 0/1.
Eigen::ArrayXXd contact_elements(const Eigen::MatrixXd& force, double force_threshold);

// Spec §1.12 f4 / §1.13 f2: CT = (1/fs) #{t : max_e b_e(t) = 1}, in seconds.
double contact_time(const Eigen::MatrixXd& force, double force_threshold, double rate_hz);

// Baselines need force referenced to the sensor's rest (spec §1.3, §1.10): every force column
// minus its rest offset, the median of its readings while its cell's proximity is >= contact_mm
// (nothing near); the channel's minimum when nothing is ever that far.
Recording remove_force_rest_offsets(const Recording& recording, const SkinLayout& layout,
                                    double contact_mm);

// Options given as words: the value of `key` in upper case, one of `allowed`; allowed[0] when
// absent. Throws tactile::Error naming the key and the allowed words otherwise.
std::string parameter_choice(const Parameters& parameters, const std::string& key,
                             const std::vector<std::string>& allowed);
// A number > 0 (or the fallback); throws tactile::Error naming the key otherwise.
double positive_parameter(const Parameters& parameters, const std::string& key, double fallback);

}  // namespace tactile
