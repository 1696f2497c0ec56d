#pragma once
// One colour per class in every view that draws classes (lanes, skin banners, signal shading,
// confusion, scatter, SOM, legends). The classes of a vocabulary (a skin's, in its display
// order) take the palette's colours in that order; a class outside it takes the next free
// place the first time it is drawn and keeps it. The palette has no grey: grey is the neutral
// colour of "unknown" (segmenter suggestions not yet classified), which no class uses.

#include <cstdint>
#include <string>
#include <vector>

namespace tactile {

// Opaque, packed as IM_COL32.
inline constexpr uint32_t kNeutralClassColour = 0xFF969696u;  // (150, 150, 150)

// The colour of place `index`: nine Tableau colours (Tableau 10 without its grey), then hues
// spread by the golden angle, so that no two places share a colour.
uint32_t class_palette_colour(size_t index);
// The index-th of a palette for many categories at once (a skin's 21 body regions): each new
// colour the farthest (CIELAB) from those before it among colours that read on the dark
// background; no two of the first 21 closer than 34 (dE76; the class palette's came within 10).
uint32_t distinct_palette_colour(size_t index);

class ClassColours {
 public:
  // `neutral`: names drawn in kNeutralClassColour (the "unknown" class).
  explicit ClassColours(std::vector<std::string> neutral = {});
  // The vocabulary in display order; names placed before and not in it keep coming after it.
  void set_vocabulary(const std::vector<std::string>& vocabulary);
  // The class's colour with `alpha` (0-255).
  uint32_t colour(const std::string& name, int alpha = 255);
  const std::vector<std::string>& order() const { return order_; }

 private:
  std::vector<std::string> neutral_;
  std::vector<std::string> order_;
};

}  // namespace tactile
