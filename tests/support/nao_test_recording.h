#pragma once
// Hand-built NAO recordings for the Kaboli feature and proximity segmenter tests: every
// proximity reads 200 mm (nothing near), every accelerometer and force 0, unless a test sets it.

#include <string>
#include <vector>

#include "tactile/io/recording.h"
#include "tactile/layout/skin_layout.h"

namespace tactile::testing {

inline constexpr double kNaoRate = 250.0;

// A recording "r" of the layout with one stream "skin" of `samples` samples.
inline Recording nao_recording(const SkinLayout& layout, int64_t samples) {
  Recording recording;
  recording.id = "r";
  recording.layout_id = layout.id;
  Stream stream;
  stream.name = "skin";
  stream.rate_hz = kNaoRate;
  for (const Channel& channel : layout.channels) {
    stream.channels.push_back(channel.name);
    stream.units.push_back(channel.unit);
  }
  stream.samples = SampleMatrix::Zero(samples, static_cast<Eigen::Index>(layout.channels.size()));
  for (size_t c = 0; c < layout.channels.size(); ++c)
    if (layout.channels[c].modality == "prox")
      stream.samples.col(static_cast<Eigen::Index>(c)).setConstant(200.0f);
  recording.streams.push_back(std::move(stream));
  return recording;
}

// The column of cell `taxel`'s modality (e.g. "ax", "f2", "prox").
inline Eigen::Index nao_column(const SkinLayout& layout, int64_t taxel,
                               const std::string& modality) {
  return layout.channel_index(layout.find_taxel(taxel)->name + "." + modality);
}

inline void set_signal(Recording& recording, const SkinLayout& layout, int64_t taxel,
                       const std::string& modality, const std::vector<double>& values,
                       int64_t first = 0) {
  auto column = recording.streams[0].samples.col(nao_column(layout, taxel, modality));
  for (size_t t = 0; t < values.size(); ++t)
    column[first + static_cast<int64_t>(t)] = static_cast<float>(values[t]);
}

inline void set_range(Recording& recording, const SkinLayout& layout, int64_t taxel,
                      const std::string& modality, int64_t first, int64_t last, float value) {
  recording.streams[0]
      .samples.col(nao_column(layout, taxel, modality))
      .segment(first, last - first)
      .setConstant(value);
}

}  // namespace tactile::testing
