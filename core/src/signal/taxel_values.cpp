#include "tactile/signal/taxel_values.h"

#include <limits>
#include <string>
#include <unordered_map>

namespace tactile {

std::vector<int> taxel_columns(const SkinLayout& layout,
                               const std::vector<std::string>& stream_channels, int modality) {
  std::unordered_map<std::string, int> column_of;
  for (size_t column = 0; column < stream_channels.size(); ++column)
    column_of.emplace(stream_channels[column], static_cast<int>(column));
  std::vector<int> columns(layout.taxels.size(), -1);
  if (modality < 0) return columns;
  for (size_t k = 0; k < layout.taxels.size(); ++k) {
    const Taxel& taxel = layout.taxels[k];
    if (modality >= static_cast<int>(taxel.channels.size())) continue;
    const int channel = taxel.channels[modality];
    if (channel < 0 || channel >= static_cast<int>(layout.channels.size())) continue;
    auto found = column_of.find(layout.channels[channel].name);
    if (found != column_of.end()) columns[k] = found->second;
  }
  return columns;
}

std::vector<float> taxel_values(const Stream& stream, const std::vector<int>& columns,
                                int64_t sample) {
  std::vector<float> values(columns.size(), std::numeric_limits<float>::quiet_NaN());
  if (sample < 0 || sample >= stream.sample_count()) return values;
  for (size_t k = 0; k < columns.size(); ++k)
    if (columns[k] >= 0 && columns[k] < stream.channel_count())
      values[k] = stream.samples(sample, columns[k]);
  return values;
}

std::vector<float> taxel_values(const std::vector<float>& channel_values,
                                const std::vector<int>& columns) {
  std::vector<float> values(columns.size(), std::numeric_limits<float>::quiet_NaN());
  for (size_t k = 0; k < columns.size(); ++k)
    if (columns[k] >= 0 && columns[k] < static_cast<int>(channel_values.size()))
      values[k] = channel_values[static_cast<size_t>(columns[k])];
  return values;
}

}  // namespace tactile
