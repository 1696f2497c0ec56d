#pragma once
// Which stream column feeds each taxel, and the taxels' values at one instant.

#include <cstdint>
#include <vector>

#include "tactile/io/recording.h"
#include "tactile/layout/skin_layout.h"

namespace tactile {

// For each taxel (layout.taxels order), the stream column holding its channel of the
// given modality, matched by channel name; -1 when the taxel has no such channel or
// the stream does not carry it.
std::vector<int> taxel_columns(const SkinLayout& layout,
                               const std::vector<std::string>& stream_channels, int modality);

// Values of those columns at one sample; NaN for taxels without a column.
std::vector<float> taxel_values(const Stream& stream, const std::vector<int>& columns,
                                int64_t sample);
// The same from every channel's value at one instant (SampleSource::values_at).
std::vector<float> taxel_values(const std::vector<float>& channel_values,
                                const std::vector<int>& columns);

}  // namespace tactile
