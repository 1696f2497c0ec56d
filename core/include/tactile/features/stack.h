#pragma once
// A stack of pipelines, "generic+raw+rocket": every pipeline's columns side by side, named
// "PIPELINE/column", so that one table holds several descriptions of the same segments and a
// search (`auto` with blocks, ml/grid_search.h) can choose among them inside each training
// fold. Each pipeline preprocesses the recording its own way (extract_segments); a segment
// that any of them skips has no row. A pipeline with no columns on a layout (grid on a strip)
// is left out of the stack on that layout (one that refuses the layout too). The pipelines
// run with their default parameters.

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "tactile/features/feature_extractor.h"

namespace tactile {

inline constexpr char kStackSeparator = '+';
inline constexpr char kStackColumnSeparator = '/';

class StackExtractor : public FeatureExtractor {
 public:
  // `names` are registered pipelines (two or more, none twice). Throws tactile::Error naming
  // an unknown one.
  explicit StackExtractor(std::vector<std::string> names);
  std::string name() const override;
  std::string description() const override;
  std::vector<FeatureColumn> columns(const SkinLayout& layout) const override;
  std::string layout_note(const SkinLayout& layout) const override;
  // One segment alone: each pipeline preprocesses the whole recording again (extract_segments
  // is the way to extract many).
  FeatureResult extract(const SegmentInput& input) const override;
  Segments extract_segments(const Recording& raw, const SkinLayout& layout,
                            const std::vector<Label>& segments,
                            const std::function<void(size_t)>& each = {}) const override;

 private:
  // The pipelines that have columns on this layout.
  std::vector<const FeatureExtractor*> present(const SkinLayout& layout) const;

  std::vector<std::string> names_;
  std::vector<std::unique_ptr<FeatureExtractor>> pipelines_;
};

// The `auto` pipeline: the stack of the pipelines for any layout, for auto to choose among
// (the whole-grid `grid` only where the taxels spread over a 2-D map).
inline constexpr std::array<const char*, 4> kAutoPipelines = {"generic", "grid", "raw", "rocket"};
std::unique_ptr<FeatureExtractor> make_auto_pipeline_extractor(const Parameters& parameters);

// "a+b+c" -> a StackExtractor; throws tactile::Error naming --params when parameters are
// given (a stack runs each pipeline with its defaults).
std::unique_ptr<FeatureExtractor> make_stack_extractor(const std::string& name,
                                                       const Parameters& parameters);

// The blocks of a stacked table's columns, "a:0-41|b:42-297" (0-based, inclusive), in column
// order; "" when the columns are not a stack of two or more pipelines.
std::string stack_blocks(const std::vector<FeatureColumn>& columns);

}  // namespace tactile
