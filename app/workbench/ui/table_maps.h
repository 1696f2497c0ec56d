#pragma once
// The maps the views draw of the results' table and of the open recording, each computed once
// on a worker (the jobs "som", "scatter" and "somatosensory") and kept until its input changes.

#include "workbench_state.h"

namespace tactile {

// The SOM map of the current table (fitted once per table, or the opened model).
bool ensure_som(WorkbenchState& state);
// The table's rows on their first two principal components (computed once per table).
bool ensure_scatter(WorkbenchState& state);
// The open recording's (or the workspace's) somatosensory map for the current modality, from
// its cache or computed on a worker; false until it is there (the view shows the job).
bool ensure_somatosensory(WorkbenchState& state);

}  // namespace tactile
