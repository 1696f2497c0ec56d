// A sixth skin from this folder alone (ring_skin.cpp: a layout, a simulator, a pipeline, one
// record): simulated, segmented, described, classified, and drawn by the workbench, with no
// file outside this folder naming it.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "cli_test_support.h"
#include "png_test_support.h"
#include "ring_skin.h"
#include "tactile/features/corpus.h"
#include "tactile/features/feature_extractor.h"
#include "tactile/io/hdf5_file.h"
#include "tactile/labels/suggestions.h"
#include "tactile/labelstore/label_store.h"
#include "tactile/ml/evaluation.h"
#include "tactile/segment/segmenter.h"
#include "tactile/skins/skin.h"
#include "tactile/skins/workspace.h"

namespace tactile {
namespace {

// The overlap of two spans over the shorter one's length.
double shared_fraction(const Label& a, const Label& b) {
  const double shared = std::min(a.t1, b.t1) - std::max(a.t0, b.t0);
  return shared / std::min(a.t1 - a.t0, b.t1 - b.t0);
}

// Pixels of viridis' upper half (teal to yellow: a taxel well above its rest), which neither
// the idle skin (dark purple) nor the plot's lines and lanes use; the colour bar has some.
int lit_taxel_pixels(const Png& png) {
  int count = 0;
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x) {
      const unsigned char* p = png.at(x, y);
      count +=
          p[1] >= 140 && p[2] >= 30 && p[2] <= 170 && (p[0] < 130 || (p[0] > 180 && p[2] < 80));
    }
  return count;
}

TEST(SixthSkin, IsSimulatedSegmentedDescribedClassifiedAndDrawnFromItsOwnFolder) {
  test::register_ring_skin();
  const test::TempFolder folder("tactile-sixth-skin");
  const std::string database = folder.file("labels.db");

  // Every list of skins knows it now.
  const std::vector<std::string> ids = skin_ids();
  EXPECT_NE(std::find(ids.begin(), ids.end(), test::kRingSkin), ids.end());
  EXPECT_EQ(default_pipeline(test::kRingSkin), "ring_motion");
  EXPECT_EQ(skin_classes(test::kRingSkin), (std::vector<std::string>{"press", "swipe"}));

  // Simulate: three subjects, six touches of each class.
  SimulationOptions options;
  options.subjects = 3;
  options.repetitions = 6;
  const SimulationSummary simulated =
      write_simulation(folder.path().string(), test::kRingSkin, options);
  ASSERT_EQ(simulated.files.size(), 3u);
  EXPECT_EQ(simulated.labels, 3 * 12);

  // Segment each recording with the skin's own segmenter: every touch is found.
  LabelStore store(database);
  const auto [method, parameters] = default_segmenter(test::kRingSkin);
  for (const std::string& file : simulated.files) {
    const Recording recording = read_recording(file);
    const SkinLayout layout = load_layout(recording.layout_id);
    std::vector<Label> segments =
        segment_recording(method, recording, layout, Parameters::parse(parameters, "segmenter"));
    LabelFilter truth_filter;
    truth_filter.recording = recording.id;
    truth_filter.source = LabelSource::kGroundTruth;
    const std::vector<Label> truth = store.list(truth_filter);
    for (const Label& touch : truth) {
      const bool found = std::any_of(segments.begin(), segments.end(), [&](const Label& segment) {
        return shared_fraction(segment, touch) > 0.5;
      });
      EXPECT_TRUE(found) << recording.id << " " << touch.class_name << " at " << touch.t0 << " s";
    }
    store.apply(segmenter_run(store, recording.id, method, std::move(segments)).edit, "test");
  }

  // Describe the segmenter's segments with the skin's pipeline (classes from the ground truth).
  const std::vector<CorpusRecording> corpus =
      corpus_from_store({database, LabelSource::kSegmenter, "", test::kRingSkin});
  const auto extractor = make_feature_extractor(default_pipeline(test::kRingSkin));
  const CorpusDataset table = extract_corpus(*extractor, corpus);
  ASSERT_GE(table.dataset.rows(), 30);
  EXPECT_EQ(table.dataset.columns.size(), 3u);

  // Classify, leaving one subject out: a press stays, a swipe travels round the ring.
  const ml::EvaluationResult result = ml::evaluate(
      table.dataset, "knn:k=3", ml::Protocol::parse("loso"), 1, ml::EvaluationControl{});
  EXPECT_GT(result.accuracy, 0.9);

  // The workbench draws its layout, found on TACTILE_LAYOUT_PATH, and lights the pressed taxels
  // during the first press (at 1.5-2.3 s) and none between touches.
  std::ofstream(folder.file("ring.json")) << test::ring_layout_json();
  ::setenv("TACTILE_LAYOUT_PATH", folder.path().c_str(), 1);
  const std::string recording = simulated.files.front();
  const auto screenshot = [&](double time, const std::string& png) {
    return test::run_program("tactile-workbench-headless",
                             recording + " --time " + std::to_string(time) +
                                 " --width 1000 --height 700 --screenshot " + folder.file(png),
                             folder);
  };
  const test::CommandResult during = screenshot(1.9, "during.png");
  const test::CommandResult between = screenshot(1.0, "between.png");
  ::unsetenv("TACTILE_LAYOUT_PATH");
  ASSERT_EQ(during.exit_code, 0) << during.err;
  ASSERT_EQ(between.exit_code, 0) << between.err;
  // The colour bar beside the map is the same in both.
  EXPECT_GT(lit_taxel_pixels(read_png(folder.file("during.png"))) -
                lit_taxel_pixels(read_png(folder.file("between.png"))),
            500);
}

}  // namespace
}  // namespace tactile
