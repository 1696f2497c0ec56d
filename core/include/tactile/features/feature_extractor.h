#pragma once
// One interface for every descriptor set: a pipeline preprocesses a whole recording
// once, then turns each labelled segment into one row of finite features (or says why
// the segment has no row).

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "tactile/io/recording.h"
#include "tactile/labelstore/label.h"
#include "tactile/layout/skin_layout.h"
#include "tactile/parameters.h"
#include "tactile/signal/sample_source.h"

namespace tactile {

struct FeatureColumn {
  std::string name;         // CSV/ARFF column name, e.g. "front.hjorth_mobility_ax"
  std::string description;  // units and the formula it implements, e.g. "Kaboli eq. (3), ax"
};

// One labelled segment of a (preprocessed) recording.
struct SegmentInput {
  const Recording& recording;
  const SkinLayout& layout;
  const Label& segment;
};

struct FeatureResult {
  std::vector<double> values;  // in columns() order; every value finite
  std::string skip_reason;     // non-empty: no row for this segment, and why
  static FeatureResult skip(std::string reason) { return {{}, std::move(reason)}; }
};

class FeatureExtractor {
 public:
  virtual ~FeatureExtractor() = default;
  virtual std::string name() const = 0;
  virtual std::string description() const = 0;
  // The columns this extractor writes for a layout (their count may depend on it).
  virtual std::vector<FeatureColumn> columns(const SkinLayout& layout) const = 0;
  // The pipeline's preprocessing of a whole recording (filters, normalisation, virtual
  // channels), run once before any segment is extracted. Default: none.
  virtual Recording preprocess(const Recording& recording, const SkinLayout& layout) const;
  virtual FeatureResult extract(const SegmentInput& input) const = 0;

  // A recording's segments, one result each in the given order, with the preprocessed
  // recording's metadata (the pipeline's notes among it). `each(done)` is called after each
  // segment (it may throw to stop). Default: preprocess once, then extract each segment; a
  // stack of pipelines runs each of its pipelines this way and joins their results.
  struct Segments {
    Metadata metadata;
    std::vector<FeatureResult> results;
  };
  virtual Segments extract_segments(const Recording& raw, const SkinLayout& layout,
                                    const std::vector<Label>& segments,
                                    const std::function<void(size_t)>& each = {}) const;
  // What the pipeline chose for this layout, in one line for the user (`tactile features`
  // prints it); empty when it has nothing to say.
  virtual std::string layout_note(const SkinLayout& layout) const;
  // True when a segment's features read only its own samples, [t0, t1) of one stream, and
  // nothing else of the recording (no preprocessing over it): a segment can then be extracted
  // from its window alone (extract_source_segments), so a long recording is never held whole.
  virtual bool reads_segment_only() const { return false; }
};

// A recording's segments from a source: each segment's window read alone when the pipeline
// reads nothing else (reads_segment_only), the same results as extract_segments on the whole
// recording; else the whole stream read once (`read_step(share)` while reading) and
// extract_segments on it. `each(done)` as extract_segments's.
FeatureExtractor::Segments extract_source_segments(
    const FeatureExtractor& extractor, const SampleSource& source, const SkinLayout& layout,
    const std::vector<Label>& segments, const std::function<void(size_t)>& each = {},
    const std::function<void(double)>& read_step = {});

// The stream a pipeline reads: the one named `name`, else the recording's first. Throws
// tactile::Error naming the recording when it has none.
const Stream& pipeline_stream(const Recording& recording, const std::string& name);
// For each layout channel, its column in `stream` (-1: the stream lacks it). When every
// stream channel is named as a layout channel they are found by name (a stream may lack a
// layout's virtual channels); otherwise the stream's channels are the layout's in order.
// Throws naming the stream when neither holds.
std::vector<int64_t> layout_columns(const Stream& stream, const SkinLayout& layout);
// Whether `stream`'s columns are the layout's channels in order.
bool in_layout_order(const Stream& stream, const SkinLayout& layout);
// `stream` with one column per layout channel in the layout's order; a channel the stream
// lacks (a virtual channel that a skin's own preprocessing computes) reads as 0.
Stream layout_ordered(const Stream& stream, const SkinLayout& layout);
// The pipeline stream of a preprocessed recording, which must be in the layout's order and
// sampled regularly; Error naming the recording and stream otherwise (`rate_need`: what the
// rate is needed for, e.g. "speeds need").
const Stream& ordered_stream(const Recording& recording, const SkinLayout& layout,
                             const std::string& name, const std::string& rate_need);
// `recording` with its pipeline stream (as pipeline_stream finds it) in the layout's order.
Recording with_layout_stream(const Recording& recording, const SkinLayout& layout,
                             const std::string& name);

// The registered pipelines: kaboli, naya, silvera_tawil, koo, tsa_event, fur,
// robovie_xcorr, flux, generic, raw, rocket, grid, auto (the stack of generic, grid, raw and
// rocket for auto to choose among), then those added by
// register_feature_pipeline. Besides these, make_feature_extractor takes a stack "a+b+c" of
// registered pipelines (features/stack.h).
std::vector<std::string> feature_pipelines();
using ExtractorFactory = std::function<std::unique_ptr<FeatureExtractor>(const Parameters&)>;
// Adds a pipeline (a new skin's), or replaces the one of the same name.
void register_feature_pipeline(const std::string& name, ExtractorFactory make);
// Throws tactile::Error naming the pipeline when unknown, or a parameter when bad.
std::unique_ptr<FeatureExtractor> make_feature_extractor(const std::string& name,
                                                         const Parameters& parameters = {});
// The settings a pipeline built from `parameters` ("key=value,...") works with: every
// parameter it reads, given or defaulted, as "key=value,..." that builds the same pipeline
// again (so a saved model keeps extracting as it was trained, whatever later defaults say).
// Throws as make_feature_extractor.
std::string effective_pipeline_parameters(const std::string& name, const std::string& parameters,
                                          const std::string& where);

}  // namespace tactile
