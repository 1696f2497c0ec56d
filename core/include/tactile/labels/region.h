#pragma once
// The region a label covers on the skin, as Label::region stores it: "all", a layout
// group's id ("left-arm", "module-07"), or an explicit set of taxels
// ("taxels:3,5,7"). Two labels may overlap in time on different regions (multi-touch).

#include <cstdint>
#include <string>
#include <vector>

#include "tactile/layout/skin_layout.h"

namespace tactile {

// The region for a selection of taxels: "all" when none or every taxel is selected,
// a group's id when the selection is exactly that group, else "taxels:ID,ID,...".
std::string region_of_taxels(const SkinLayout& layout, std::vector<int64_t> taxels);

// The taxels of a region, sorted; empty for a region the layout does not know.
std::vector<int64_t> taxels_of_region(const SkinLayout& layout, const std::string& region);

}  // namespace tactile
