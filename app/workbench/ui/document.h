#pragma once
// The recording open in the workbench: its samples, its layout, the plot pyramids of
// its channels and its labels.

#include <memory>
#include <string>
#include <vector>

#include "tactile/io/label.h"
#include "tactile/io/recording.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/signal/minmax_pyramid.h"

namespace tactile {

struct Document {
  std::string path;
  std::string labels_path;  // "" when the recording has no label database beside it
  Recording recording;
  SkinLayout layout;
  int stream_index = 0;
  std::vector<MinMaxPyramid> pyramids;  // one per channel of the current stream
  std::vector<Label> labels;

  const Stream& stream() const { return recording.streams[static_cast<size_t>(stream_index)]; }
};

// Reads a recording (HDF5) and its layout; labels come from `labels_path`, or else
// from labels.db in the recording's folder when there is one. Throws tactile::Error.
std::unique_ptr<Document> open_document(const std::string& path,
                                        const std::string& labels_path = {});
// Selects another stream and rebuilds the pyramids.
void select_stream(Document& document, int stream_index);

}  // namespace tactile
