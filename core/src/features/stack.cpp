#include "tactile/features/stack.h"

#include <algorithm>

#include "tactile/error.h"
#include "tactile/text.h"

namespace tactile {

StackExtractor::StackExtractor(std::vector<std::string> names) : names_(std::move(names)) {
  const std::string where = "pipeline " + name();
  if (names_.size() < 2)
    throw Error(where, "a stack needs two or more pipelines, e.g. generic+raw");
  for (size_t i = 0; i < names_.size(); ++i) {
    if (names_[i].empty()) throw Error(where, "an empty pipeline name");
    if (std::find(names_.begin(), names_.begin() + static_cast<std::ptrdiff_t>(i), names_[i]) !=
        names_.begin() + static_cast<std::ptrdiff_t>(i))
      throw Error(where, "pipeline " + names_[i] + " twice");
    pipelines_.push_back(make_feature_extractor(names_[i]));
  }
}

std::string StackExtractor::name() const {
  std::string text;
  for (const std::string& part : names_)
    text += (text.empty() ? "" : std::string(1, kStackSeparator)) + part;
  return text;
}

std::string StackExtractor::layout_note(const SkinLayout& layout) const {
  std::string note;
  for (const FeatureExtractor* pipeline : present(layout)) {
    const std::string part = pipeline->layout_note(layout);
    if (!part.empty()) note += (note.empty() ? "" : "; ") + part;
  }
  return note;
}

std::string StackExtractor::description() const {
  return "the columns of " + joined(names_) + " side by side, each named PIPELINE/column";
}

std::vector<const FeatureExtractor*> StackExtractor::present(const SkinLayout& layout) const {
  std::vector<const FeatureExtractor*> kept;
  for (const auto& pipeline : pipelines_) {
    try {
      if (!pipeline->columns(layout).empty()) kept.push_back(pipeline.get());
    } catch (const Error&) {
      // A pipeline this layout cannot have (grid on a strip) is left out of the stack.
    }
  }
  if (kept.empty())
    throw Error("pipeline " + name(), "none of its pipelines has columns on layout " + layout.id);
  return kept;
}

std::vector<FeatureColumn> StackExtractor::columns(const SkinLayout& layout) const {
  std::vector<FeatureColumn> all;
  for (const FeatureExtractor* pipeline : present(layout))
    for (FeatureColumn column : pipeline->columns(layout)) {
      column.name = pipeline->name() + kStackColumnSeparator + column.name;
      all.push_back(std::move(column));
    }
  return all;
}

FeatureResult StackExtractor::extract(const SegmentInput& input) const {
  Segments one = extract_segments(input.recording, input.layout, {input.segment});
  return std::move(one.results.front());
}

StackExtractor::Segments StackExtractor::extract_segments(
    const Recording& raw, const SkinLayout& layout, const std::vector<Label>& segments,
    const std::function<void(size_t)>& each) const {
  const std::vector<const FeatureExtractor*> kept = present(layout);
  Segments joined_rows;
  joined_rows.results.resize(segments.size());
  for (size_t k = 0; k < kept.size(); ++k) {
    const size_t before = k * segments.size();
    Segments part = kept[k]->extract_segments(raw, layout, segments, [&](size_t done) {
      if (each) each((before + done) / kept.size());
    });
    for (const auto& [key, value] : part.metadata) joined_rows.metadata.emplace(key, value);
    for (size_t s = 0; s < segments.size(); ++s) {
      FeatureResult& row = joined_rows.results[s];
      if (!row.skip_reason.empty()) continue;
      FeatureResult& piece = part.results[s];
      if (!piece.skip_reason.empty()) {
        row = FeatureResult::skip(kept[k]->name() + ": " + piece.skip_reason);
        continue;
      }
      row.values.insert(row.values.end(), piece.values.begin(), piece.values.end());
    }
  }
  return joined_rows;
}

std::unique_ptr<FeatureExtractor> make_auto_pipeline_extractor(const Parameters& parameters) {
  if (!parameters.values().empty())
    throw Error(
        "--params",
        "the auto pipeline runs each of its pipelines with its defaults and takes no parameters");
  return std::make_unique<StackExtractor>(
      std::vector<std::string>(kAutoPipelines.begin(), kAutoPipelines.end()));
}

std::unique_ptr<FeatureExtractor> make_stack_extractor(const std::string& name,
                                                       const Parameters& parameters) {
  if (!parameters.values().empty())
    throw Error("--params", "a stack of pipelines (" + name +
                                ") runs each with its defaults and takes no parameters");
  std::vector<std::string> names;
  size_t start = 0;
  while (start <= name.size()) {
    const size_t plus = std::min(name.find(kStackSeparator, start), name.size());
    names.push_back(name.substr(start, plus - start));
    start = plus + 1;
  }
  return std::make_unique<StackExtractor>(std::move(names));
}

std::string stack_blocks(const std::vector<FeatureColumn>& columns) {
  struct Block {
    std::string pipeline;
    size_t first = 0, last = 0;
  };
  std::vector<Block> blocks;
  for (size_t c = 0; c < columns.size(); ++c) {
    const size_t slash = columns[c].name.find(kStackColumnSeparator);
    if (slash == std::string::npos || slash == 0) return "";
    const std::string pipeline = columns[c].name.substr(0, slash);
    if (!blocks.empty() && blocks.back().pipeline == pipeline) {
      blocks.back().last = c;
      continue;
    }
    // A pipeline's columns apart from each other: not a stack.
    for (const Block& block : blocks)
      if (block.pipeline == pipeline) return "";
    blocks.push_back({pipeline, c, c});
  }
  if (blocks.size() < 2) return "";
  std::string text;
  for (const Block& block : blocks)
    text += (text.empty() ? "" : "|") + block.pipeline + ":" + std::to_string(block.first) + "-" +
            std::to_string(block.last);
  return text;
}

}  // namespace tactile
