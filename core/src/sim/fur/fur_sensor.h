#pragma once
// The smart-fur pressure matrix of paper 002 §2.1 as a physical device: plush and a stiff
// carrier spread the hand's pressure; each Velostat cell conducts more the more of its
// area is pressed (bigger cell, more signal); the cell and the microcontroller's pull-up
// form a divider read by a 10-bit ADC; rows and columns of the matrix leak into their
// neighbours; the fur and fleece settle after a contact, shifting the quiescent reading;
// the microcontroller low-pass filters its 1 kHz samples and sends 15 Hz frames.

#include <cstdint>
#include <vector>

#include "fur_hand.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/sim/sim_util.h"

namespace tactile::sim::fur {

class FurSensor {
 public:
  // Cells are the layout's taxels; matrix rows are taxels sharing a map row, columns their
  // order along it, and the two halves of a row share ADC lines (the diode doubling).
  // Per-cell manufacturing spread is drawn from `device`.
  FurSensor(const SkinLayout& layout, Random& device);

  int cell_count() const { return static_cast<int>(cells_.size()); }
  // Recording column of a cell (its channel in the layout).
  int channel(int cell) const { return cells_[cell].channel; }
  int64_t taxel_id(int cell) const { return cells_[cell].taxel_id; }

  // Starts a new instant: no pressure anywhere.
  void clear_pressure();
  // Adds one contact ellipse's pressure, spread by the plush, to the cells under it.
  void press(const ContactPart& part);
  // Contact noise of the Velostat for the next frame: one factor per cell.
  void draw_contact_jitter(Random& random);
  // Advances the fur's settling, the ADC and the microcontroller's low-pass by dt.
  void advance(double dt);

  // Low-passed ADC reading of each cell (counts, before the frame is rounded).
  const std::vector<double>& filtered() const { return filtered_; }
  // Normal force each cell carries at this instant (N): ground truth for regions.
  const std::vector<double>& cell_force() const { return cell_force_; }
  // Slowly drifting quiescent level, as a factor on every cell's resting conductance.
  void set_drift(double factor) { drift_ = factor; }

  // Steady reading (counts) of a cell at rest and under a reference press of `force` N
  // by a soft-tipped cylinder of `diameter` mm at its centre (paper 002 Fig 5).
  double rest_reading(int cell) const;
  double reading_under_reference(int cell, double force, double diameter);

 private:
  struct Neighbour {
    int cell = 0;
    double coupling = 0.0;
  };
  struct Cell {
    Point2 centre, half_size;
    double area = 0.0;
    double gain = 1.0;              // conductance per unit pressure^beta, from the cell's area
    double rest_conductance = 0.0;  // in units of the pull-up's conductance
    int channel = 0;
    int64_t taxel_id = 0;
    std::vector<Neighbour> neighbours;  // crosstalk of the matrix scan
  };

  double touch_conductance(int cell) const;
  double adc_reading(double conductance) const;

  std::vector<Cell> cells_;
  std::vector<float> pressure_;  // kPa at each cell's sub-points
  std::vector<uint8_t> touched_;
  std::vector<double> jitter_, touch_, residual_, permanent_, filtered_, cell_force_;
  double drift_ = 1.0;
};

}  // namespace tactile::sim::fur
