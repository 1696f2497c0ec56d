#pragma once
// The way from a confusion cell to its segments and back: the cell's list, the landing on
// one segment (its recording opened, replayed on the skin) and the walk through the mistakes.

#include "workbench_state.h"

namespace tactile {

// Selects a confusion cell: its segments become the list, the first selected.
void select_cell(WorkbenchState& state, int truth, int predicted);
// Goes to one prediction's segment: opens its recording, moves the cursor and the plot
// to it, replays it on the skin with its region outlined, both classes named.
void land_on(WorkbenchState& state, const ml::RowPrediction& row);
// The next (+1) or previous (-1) misclassified prediction after the landed one.
bool walk_misclassified(WorkbenchState& state, int direction);
// Carries out a landing asked for by land_on (after the frame: it may open a file).
void carry_out_landing(WorkbenchState& state);

}  // namespace tactile
