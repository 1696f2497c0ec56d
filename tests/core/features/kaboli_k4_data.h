#pragma once
// Test vector K4 (TEST_VECTORS.md): three NAO cells, T = 8 samples, proximity minima 20, 45 and
// exactly 50 mm; shared by the Kaboli descriptor and the adapted baseline tests (K5-K7).

#include <string>
#include <vector>

#include "nao_test_recording.h"
#include "tactile/labelstore/label.h"

namespace tactile::testing {

using Vector = std::vector<double>;

struct K4Cell {
  Vector ax, ay, az;
  std::vector<Vector> force;
};

inline const std::vector<K4Cell>& k4_cells() {
  static const std::vector<K4Cell> cells = {
      {{0, 1, 0.5, -1, 0, 1.5, 0, -1},
       {0, 0.5, 1, 0.5, 0, -0.5, -1, -0.5},
       {1, 1, 2, 2, 1, 1, 2, 2},
       {{0, 0.2, 0.8, 1, 0.6, 0.2, 0, 0},
        {0, 0.1, 0.4, 0.5, 0.3, 0.1, 0, 0},
        {0, 0, 0.2, 0.3, 0.2, 0, 0, 0}}},
      {{0, 2, 1, 3, 2, 4, 3, 5},
       {1, 0, 1, 0, 1, 0, 1, 0},
       {0, 1, 1, 0, 0, 1, 1, 0},
       {{0, 0, 0.1, 0.6, 0.9, 0.4, 0.1, 0}, {0, 0, 0, 0.2, 0.4, 0.2, 0, 0}, Vector(8, 0.1)}},
      {Vector(8, 5),
       {1, 2, 1, 2, 1, 2, 1, 2},
       Vector(8, 0),
       {Vector(8, 0), Vector(8, 0), Vector(8, 0)}},
  };
  return cells;
}

// The NAO layout with its front reduced to cells 1-3, carrying K4's signals in samples 0-7
// (proximity minima 20, 45 and exactly 50 mm), followed by 12 samples of rest.
struct K4Recording {
  SkinLayout layout;
  Recording recording;
};

inline K4Recording k4_recording() {
  K4Recording k4{load_layout("nao"), {}};
  for (Group& group : k4.layout.groups)
    if (group.id == "front") group.taxels = {1, 2, 3};
  k4.recording = nao_recording(k4.layout, 20);
  const std::vector<Vector> proximity = {
      {200, 20, 30, 40, 60, 200, 200, 200}, {200, 100, 45, 47, 80, 200, 200, 200}, Vector(8, 50.0)};
  for (int64_t cell = 1; cell <= 3; ++cell) {
    const K4Cell& signals = k4_cells()[static_cast<size_t>(cell - 1)];
    set_signal(k4.recording, k4.layout, cell, "ax", signals.ax);
    set_signal(k4.recording, k4.layout, cell, "ay", signals.ay);
    set_signal(k4.recording, k4.layout, cell, "az", signals.az);
    const char* const force_modalities[] = {"f1", "f2", "f3"};
    for (size_t f = 0; f < 3; ++f)
      set_signal(k4.recording, k4.layout, cell, force_modalities[f], signals.force[f]);
    set_signal(k4.recording, k4.layout, cell, "prox", proximity[static_cast<size_t>(cell - 1)]);
  }
  return k4;
}

// A segment of the K4 recording ("r") over `region`.
inline Label segment(double t0, double t1, const std::string& region) {
  Label label;
  label.recording = "r";
  label.t0 = t0;
  label.t1 = t1;
  label.region = region;
  return label;
}

}  // namespace tactile::testing
