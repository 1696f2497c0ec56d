#pragma once
// The somatosensory map (Robovie paper, spec §4.8): each taxel placed by classical MDS of
// the correlation distances d_ij = -ln |R_ij| between the taxels' signals, so taxels that
// are touched together lie together, whatever the body says. Computed over one recording
// or a corpus (correlations from pooled sums), chunk by chunk through the SampleSource,
// and cached beside the data.

#include <cstdint>
#include <functional>
#include <map>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "tactile/layout/skin_layout.h"
#include "tactile/signal/sample_source.h"

namespace tactile {

struct SomatosensoryMap {
  std::string layout;
  std::string modality;
  std::vector<int64_t> taxels;             // taxel ids, layout order, those with a channel
  std::vector<Point2> positions;           // per taxel, scaled into the body map's bounding box
  double negative_eigenvalue_ratio = 0.0;  // how far d is from Euclidean (ml::MdsResult)
  int64_t samples = 0;                     // samples the correlations were computed over
  std::string source;                      // what it was computed over (file names)
};

// Pools the sums of Pearson correlation over several sources (a corpus of one skin).
class CorrelationSums {
 public:
  explicit CorrelationSums(int taxels);
  // Adds every sample of the given columns (one per taxel, -1: absent, left at zero),
  // reading `block` samples at a time; `step(fraction of the source)` is called after each
  // block (a job reports progress there, and ends there when cancelled: the callback throws).
  void add(const SampleSource& source, const std::vector<int>& columns, int64_t block = 8192,
           const std::function<void(double)>& step = {});
  // R; a taxel that never varied correlates 0 with every other (1 with itself).
  Eigen::MatrixXd correlation() const;
  int64_t samples() const { return count_; }

 private:
  Eigen::VectorXd sum_;
  Eigen::MatrixXd products_;
  int64_t count_ = 0;
};

// The map from pooled correlations: d = correlation_dissimilarity(R), classical MDS to 2-D,
// coordinates scaled (one factor for both axes) into the bounding box of the taxels'
// body-map positions. Throws tactile::Error when fewer than 3 taxels have a channel.
SomatosensoryMap somatosensory_map(const SkinLayout& layout, int modality,
                                   const std::vector<int64_t>& taxels,
                                   const Eigen::MatrixXd& correlation);
// Over one source's whole span.
SomatosensoryMap somatosensory_map(const SampleSource& source, const SkinLayout& layout,
                                   int modality, const std::function<void(double)>& step = {});

// How far a map keeps the body (Robovie paper, Fig. 8: films of one body part lie together):
// per taxel, the share of its `neighbours` nearest taxels on the map that lie on its own body
// part (Taxel::body_part), averaged over the taxels; the share a map placing taxels at random
// would reach; and Spearman's rank correlation, over every pair of taxels, between their
// distance on the map and on the body map (Taxel::position).
struct MapBodyAgreement {
  int neighbours = 5;
  double same_part_share = 0.0;
  double chance_share = 0.0;
  double rank_correlation = 0.0;
  // same_part_share per body part (over that part's taxels), by part name: which parts
  // gather and which lie scattered.
  std::map<std::string, double> part_share;
};
// Throws tactile::Error when the map has fewer taxels than neighbours + 1, or a taxel the
// layout lacks.
MapBodyAgreement map_body_agreement(const SomatosensoryMap& map, const SkinLayout& layout,
                                    int neighbours = 5);

nlohmann::json to_json(const SomatosensoryMap& map);
SomatosensoryMap somatosensory_from_json(const nlohmann::json& document, const std::string& where);

// The cache beside a recording: RECORDING.h5 -> RECORDING.somatosensory-MODALITY.json,
// valid while the recording's size and modification time are those stored in it.
std::string somatosensory_cache_path(const std::string& recording_path,
                                     const std::string& modality);
std::optional<SomatosensoryMap> read_somatosensory_cache(const std::string& recording_path,
                                                         const std::string& modality);
// Best effort: a folder that cannot be written leaves no cache (returns false).
bool write_somatosensory_cache(const std::string& recording_path, const SomatosensoryMap& map);

// Over a corpus: every recording (files of the same skin) pooled into one correlation;
// `step(fraction of the corpus)` as in CorrelationSums::add.
// Throws tactile::Error naming a file of another skin, or one that cannot be read.
SomatosensoryMap somatosensory_corpus_map(const std::vector<std::string>& recordings,
                                          const SkinLayout& layout, int modality,
                                          const std::function<void(double)>& step = {});
// The corpus cache: FOLDER/LAYOUT.somatosensory-MODALITY.json, valid while every
// recording's size and modification time are those stored (and no file came or went).
std::string somatosensory_corpus_cache_path(const std::string& folder, const std::string& layout,
                                            const std::string& modality);
std::optional<SomatosensoryMap> read_somatosensory_corpus_cache(
    const std::string& cache_path, const std::vector<std::string>& recordings);
bool write_somatosensory_corpus_cache(const std::string& cache_path,
                                      const std::vector<std::string>& recordings,
                                      const SomatosensoryMap& map);

// The layout with its taxels moved to the map's positions (drawn as small circles) and
// without its body outline; taxels not on the map keep their place.
SkinLayout layout_on_map(const SkinLayout& layout, const SomatosensoryMap& map);

}  // namespace tactile
