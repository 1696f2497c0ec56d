#include "tactile/labels/region.h"

#include <algorithm>
#include <charconv>

namespace tactile {

namespace {

constexpr const char* kTaxelsPrefix = "taxels:";

std::vector<int64_t> sorted_unique(std::vector<int64_t> ids) {
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

std::vector<int64_t> all_taxels(const SkinLayout& layout) {
  std::vector<int64_t> ids;
  for (const Taxel& taxel : layout.taxels) ids.push_back(taxel.id);
  return sorted_unique(std::move(ids));
}

}  // namespace

std::string region_of_taxels(const SkinLayout& layout, std::vector<int64_t> taxels) {
  taxels = sorted_unique(std::move(taxels));
  if (taxels.empty() || taxels == all_taxels(layout)) return "all";
  for (const Group& group : layout.groups)
    if (sorted_unique(group.taxels) == taxels) return group.id;
  std::string region = kTaxelsPrefix;
  for (size_t k = 0; k < taxels.size(); ++k) region += (k ? "," : "") + std::to_string(taxels[k]);
  return region;
}

std::vector<int64_t> taxels_of_region(const SkinLayout& layout, const std::string& region) {
  if (region == "all") return all_taxels(layout);
  for (const Group& group : layout.groups)
    if (group.id == region) return sorted_unique(group.taxels);
  if (!region.starts_with(kTaxelsPrefix)) return {};
  std::vector<int64_t> ids;
  const char* at = region.data() + std::char_traits<char>::length(kTaxelsPrefix);
  const char* end = region.data() + region.size();
  while (at < end) {
    int64_t id = 0;
    const auto [next, error] = std::from_chars(at, end, id);
    if (error != std::errc()) return {};
    ids.push_back(id);
    at = next;
    if (at < end && *at != ',') return {};
    if (at < end) ++at;
  }
  return sorted_unique(std::move(ids));
}

}  // namespace tactile
