// Somatosensory map: pooled Pearson correlations -> -ln|R| -> classical MDS (spec §4.8).
#include "tactile/ml/somatosensory.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "tactile/error.h"
#include "tactile/io/atomic_file.h"
#include "tactile/ml/mds.h"
#include "tactile/signal/taxel_values.h"
#include "tactile/stats/statistics.h"

namespace tactile {

namespace fs = std::filesystem;

CorrelationSums::CorrelationSums(int taxels)
    : sum_(Eigen::VectorXd::Zero(taxels)), products_(Eigen::MatrixXd::Zero(taxels, taxels)) {}

void CorrelationSums::add(const SampleSource& source, const std::vector<int>& columns,
                          int64_t block, const std::function<void(double)>& step) {
  if (static_cast<Eigen::Index>(columns.size()) != sum_.size())
    throw Error("somatosensory map", "expected " + std::to_string(sum_.size()) + " columns, got " +
                                         std::to_string(columns.size()));
  std::vector<int> present;
  std::vector<Eigen::Index> slot;
  for (size_t k = 0; k < columns.size(); ++k)
    if (columns[k] >= 0)
      present.push_back(columns[k]), slot.push_back(static_cast<Eigen::Index>(k));
  if (present.empty()) return;
  const int64_t total = source.sample_count();
  for (int64_t first = 0; first < total; first += block) {
    if (step) step(static_cast<double>(first) / static_cast<double>(total));
    const int64_t count = std::min(block, total - first);
    const Eigen::MatrixXd samples = source.read(present, first, count).cast<double>();
    // Rows with a gap (NaN: a damaged chunk) are left out.
    Eigen::MatrixXd block_samples = samples;
    Eigen::Index kept = 0;
    for (Eigen::Index row = 0; row < samples.rows(); ++row)
      if (samples.row(row).allFinite()) block_samples.row(kept++) = samples.row(row);
    const auto used = block_samples.topRows(kept);
    const Eigen::VectorXd sums = used.colwise().sum().transpose();
    const Eigen::MatrixXd products = used.transpose() * used;
    for (size_t i = 0; i < slot.size(); ++i) {
      sum_(slot[i]) += sums(static_cast<Eigen::Index>(i));
      for (size_t j = 0; j < slot.size(); ++j)
        products_(slot[i], slot[j]) +=
            products(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
    }
    count_ += kept;
  }
}

Eigen::MatrixXd CorrelationSums::correlation() const {
  const Eigen::Index n = sum_.size();
  Eigen::MatrixXd r = Eigen::MatrixXd::Identity(n, n);
  if (count_ < 2) return r;
  const double count = static_cast<double>(count_);
  const Eigen::VectorXd mean = sum_ / count;
  Eigen::MatrixXd covariance = products_ / count - mean * mean.transpose();
  Eigen::VectorXd deviation(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double variance = covariance(i, i);
    // A taxel that never varied (or is absent) has no correlation with anything.
    deviation(i) = variance > 1e-12 * std::max(1.0, mean(i) * mean(i)) ? std::sqrt(variance) : 0.0;
  }
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j)
      if (i != j)
        r(i, j) = deviation(i) > 0 && deviation(j) > 0
                      ? std::clamp(covariance(i, j) / (deviation(i) * deviation(j)), -1.0, 1.0)
                      : 0.0;
  return r;
}

SomatosensoryMap somatosensory_map(const SkinLayout& layout, int modality,
                                   const std::vector<int64_t>& taxels,
                                   const Eigen::MatrixXd& correlation) {
  if (taxels.size() < 3)
    throw Error("somatosensory map",
                "needs at least 3 taxels with a channel, has " + std::to_string(taxels.size()));
  const ml::MdsResult mds = ml::classical_mds(ml::correlation_dissimilarity(correlation), 2);
  SomatosensoryMap map;
  map.layout = layout.id;
  map.modality = modality >= 0 && modality < static_cast<int>(layout.modalities.size())
                     ? layout.modalities[static_cast<size_t>(modality)]
                     : "";
  map.taxels = taxels;
  map.negative_eigenvalue_ratio = mds.negative_eigenvalue_ratio;
  // Into the body map's bounding box, one scale for both axes, centred.
  double x0 = std::numeric_limits<double>::max(), y0 = x0, x1 = -x0, y1 = -x0;
  for (const Taxel& taxel : layout.taxels) {
    x0 = std::min(x0, taxel.position.x), x1 = std::max(x1, taxel.position.x);
    y0 = std::min(y0, taxel.position.y), y1 = std::max(y1, taxel.position.y);
  }
  const Eigen::MatrixXd& xy = mds.coordinates;
  const double u0 = xy.col(0).minCoeff(), u1 = xy.col(0).maxCoeff();
  const double v0 = xy.col(1).minCoeff(), v1 = xy.col(1).maxCoeff();
  const double width = std::max(x1 - x0, 1.0), height = std::max(y1 - y0, 1.0);
  const double scale =
      std::min(width / std::max(u1 - u0, 1e-12), height / std::max(v1 - v0, 1e-12));
  for (Eigen::Index i = 0; i < xy.rows(); ++i)
    map.positions.push_back({x0 + width / 2 + (xy(i, 0) - (u0 + u1) / 2) * scale,
                             y0 + height / 2 + (xy(i, 1) - (v0 + v1) / 2) * scale});
  return map;
}

SomatosensoryMap somatosensory_map(const SampleSource& source, const SkinLayout& layout,
                                   int modality, const std::function<void(double)>& step) {
  const std::vector<int> all = taxel_columns(layout, source.info().channels, modality);
  std::vector<int> columns;
  std::vector<int64_t> taxels;
  for (size_t k = 0; k < all.size(); ++k)
    if (all[k] >= 0) columns.push_back(all[k]), taxels.push_back(layout.taxels[k].id);
  CorrelationSums sums(static_cast<int>(columns.size()));
  sums.add(source, columns, 8192, step);
  SomatosensoryMap map = somatosensory_map(layout, modality, taxels, sums.correlation());
  map.samples = sums.samples();
  map.source = source.info().recording_id;
  return map;
}

nlohmann::json to_json(const SomatosensoryMap& map) {
  nlohmann::json positions = nlohmann::json::array();
  for (const Point2& point : map.positions) positions.push_back({point.x, point.y});
  return {{"layout", map.layout},
          {"modality", map.modality},
          {"taxels", map.taxels},
          {"positions", positions},
          {"samples", map.samples},
          {"source", map.source},
          {"negative_eigenvalue_ratio", map.negative_eigenvalue_ratio}};
}

SomatosensoryMap somatosensory_from_json(const nlohmann::json& document, const std::string& where) {
  SomatosensoryMap map;
  try {
    map.layout = document.at("layout").get<std::string>();
    map.modality = document.at("modality").get<std::string>();
    map.taxels = document.at("taxels").get<std::vector<int64_t>>();
    for (const nlohmann::json& point : document.at("positions")) {
      const auto xy = point.get<std::vector<double>>();
      if (xy.size() != 2 || !std::isfinite(xy[0]) || !std::isfinite(xy[1]))
        throw Error(where, "a position is not two finite numbers");
      map.positions.push_back({xy[0], xy[1]});
    }
    map.samples = document.value("samples", int64_t{0});
    map.source = document.value("source", std::string());
    map.negative_eigenvalue_ratio = document.value("negative_eigenvalue_ratio", 0.0);
  } catch (const nlohmann::json::exception& error) {
    throw Error(where, std::string("malformed somatosensory map: ") + error.what());
  }
  if (map.positions.size() != map.taxels.size())
    throw Error(where, "positions and taxels differ in number");
  return map;
}

namespace {

// What identifies the recording's bytes well enough for a cache: size and mtime.
std::string file_stamp(const std::string& path) {
  std::error_code error;
  const auto size = fs::file_size(path, error);
  if (error) return "";
  const auto time = fs::last_write_time(path, error);
  if (error) return "";
  return std::to_string(size) + ":" + std::to_string(time.time_since_epoch().count());
}

}  // namespace

std::string somatosensory_cache_path(const std::string& recording_path,
                                     const std::string& modality) {
  fs::path path(recording_path);
  path.replace_extension();
  return path.string() + ".somatosensory-" + modality + ".json";
}

namespace {

std::optional<SomatosensoryMap> read_cache(const std::string& path, const std::string& stamp) {
  std::ifstream in(path);
  if (!in || stamp.empty()) return std::nullopt;
  const nlohmann::json document = nlohmann::json::parse(in, nullptr, false);
  if (document.is_discarded() || !document.is_object() ||
      document.value("stamp", std::string()) != stamp)
    return std::nullopt;  // stale or damaged: computed again
  try {
    return somatosensory_from_json(document, path);
  } catch (const Error&) {
    return std::nullopt;
  }
}

bool write_cache(const std::string& path, const std::string& stamp, const SomatosensoryMap& map) {
  if (stamp.empty()) return false;
  nlohmann::json document = to_json(map);
  document["stamp"] = stamp;
  try {
    write_file_atomically(path, document.dump() + "\n", "somatosensory map cache");
  } catch (const Error&) {
    return false;  // a folder that cannot be written: no cache, the map is still shown
  }
  return true;
}

std::string corpus_stamp(std::vector<std::string> recordings) {
  std::sort(recordings.begin(), recordings.end());
  std::string stamp;
  for (const std::string& path : recordings) {
    const std::string one = file_stamp(path);
    if (one.empty()) return "";
    stamp += fs::path(path).filename().string() + "=" + one + ";";
  }
  return stamp;
}

}  // namespace

std::optional<SomatosensoryMap> read_somatosensory_cache(const std::string& recording_path,
                                                         const std::string& modality) {
  return read_cache(somatosensory_cache_path(recording_path, modality), file_stamp(recording_path));
}

bool write_somatosensory_cache(const std::string& recording_path, const SomatosensoryMap& map) {
  return write_cache(somatosensory_cache_path(recording_path, map.modality),
                     file_stamp(recording_path), map);
}

SomatosensoryMap somatosensory_corpus_map(const std::vector<std::string>& recordings,
                                          const SkinLayout& layout, int modality,
                                          const std::function<void(double)>& step) {
  std::vector<int64_t> taxels;
  std::unique_ptr<CorrelationSums> sums;
  std::string names;
  for (size_t file = 0; file < recordings.size(); ++file) {
    const std::string& path = recordings[file];
    const FileSampleSource source(path);
    if (source.info().layout_id != layout.id)
      throw Error(path, "a recording of skin '" + source.info().layout_id + "', the map is of '" +
                            layout.id + "'");
    const std::vector<int> all = taxel_columns(layout, source.info().channels, modality);
    std::vector<int> columns;
    std::vector<int64_t> present;
    for (size_t k = 0; k < all.size(); ++k)
      if (all[k] >= 0) columns.push_back(all[k]), present.push_back(layout.taxels[k].id);
    if (!sums) {
      taxels = present;
      sums = std::make_unique<CorrelationSums>(static_cast<int>(taxels.size()));
    } else if (present != taxels) {
      throw Error(path, "carries other taxels than the first recording of the corpus");
    }
    const double done = static_cast<double>(file), files = static_cast<double>(recordings.size());
    sums->add(source, columns, 8192, [&](double fraction) {
      if (step) step((done + fraction) / files);
    });
    names += (names.empty() ? "" : ", ") + fs::path(path).filename().string();
  }
  if (!sums) throw Error("somatosensory map", "no recordings in the corpus");
  SomatosensoryMap map = somatosensory_map(layout, modality, taxels, sums->correlation());
  map.samples = sums->samples();
  map.source = names;
  return map;
}

std::string somatosensory_corpus_cache_path(const std::string& folder, const std::string& layout,
                                            const std::string& modality) {
  return (fs::path(folder) / (layout + ".somatosensory-" + modality + ".json")).string();
}

std::optional<SomatosensoryMap> read_somatosensory_corpus_cache(
    const std::string& cache_path, const std::vector<std::string>& recordings) {
  return read_cache(cache_path, corpus_stamp(recordings));
}

bool write_somatosensory_corpus_cache(const std::string& cache_path,
                                      const std::vector<std::string>& recordings,
                                      const SomatosensoryMap& map) {
  return write_cache(cache_path, corpus_stamp(recordings), map);
}

SkinLayout layout_on_map(const SkinLayout& layout, const SomatosensoryMap& map) {
  SkinLayout moved = layout;
  moved.body_outline.clear();  // the taxels have left the body: its outline would mislead
  // A dot's size: a fraction of the map, so 274 films do not cover each other.
  double x0 = 1e300, x1 = -1e300;
  for (const Point2& point : map.positions) x0 = std::min(x0, point.x), x1 = std::max(x1, point.x);
  const double dot =
      std::max(1.0, (x1 - x0) / std::max(8.0, std::sqrt(map.positions.size()) * 3.0));
  for (size_t k = 0; k < map.taxels.size(); ++k)
    for (Taxel& taxel : moved.taxels)
      if (taxel.id == map.taxels[k]) {
        taxel.position = map.positions[k];
        taxel.size = {dot, dot};
        taxel.shape = TaxelShape::kCircle;
        taxel.outline.clear();
      }
  return moved;
}

MapBodyAgreement map_body_agreement(const SomatosensoryMap& map, const SkinLayout& layout,
                                    int neighbours) {
  const size_t count = map.taxels.size();
  if (neighbours < 1 || count < static_cast<size_t>(neighbours) + 1)
    throw Error("somatosensory map", "needs more than " + std::to_string(neighbours) +
                                         " taxels to count neighbours, has " +
                                         std::to_string(count));
  std::vector<const Taxel*> taxels;
  for (int64_t id : map.taxels) {
    const Taxel* taxel = layout.find_taxel(id);
    if (!taxel)
      throw Error("somatosensory map",
                  "taxel " + std::to_string(id) + " is not in layout " + layout.id);
    taxels.push_back(taxel);
  }
  MapBodyAgreement agreement;
  agreement.neighbours = neighbours;
  auto map_distance = [&](size_t i, size_t j) {
    return std::hypot(map.positions[i].x - map.positions[j].x,
                      map.positions[i].y - map.positions[j].y);
  };
  std::vector<double> on_map, on_body;
  on_map.reserve(count * (count - 1) / 2);
  on_body.reserve(count * (count - 1) / 2);
  std::vector<std::pair<double, size_t>> nearest(count - 1);
  double share = 0.0;
  for (size_t i = 0; i < count; ++i) {
    size_t k = 0;
    for (size_t j = 0; j < count; ++j)
      if (j != i) nearest[k++] = {map_distance(i, j), j};
    std::partial_sort(nearest.begin(), nearest.begin() + neighbours, nearest.end());
    int same = 0;
    for (int n = 0; n < neighbours; ++n)
      same += taxels[nearest[static_cast<size_t>(n)].second]->body_part == taxels[i]->body_part;
    share += static_cast<double>(same) / neighbours;
    agreement.part_share[taxels[i]->body_part] += static_cast<double>(same) / neighbours;
    for (size_t j = i + 1; j < count; ++j) {
      on_map.push_back(map_distance(i, j));
      on_body.push_back(std::hypot(taxels[i]->position.x - taxels[j]->position.x,
                                   taxels[i]->position.y - taxels[j]->position.y));
    }
  }
  agreement.same_part_share = share / static_cast<double>(count);
  // At random, a taxel's neighbour is another taxel of its part with the share of those among
  // the others.
  std::map<std::string, double> parts;
  for (const Taxel* taxel : taxels) parts[taxel->body_part] += 1.0;
  for (auto& [part, summed] : agreement.part_share) summed /= parts[part];
  double chance = 0.0;
  for (const auto& [part, size] : parts) chance += size * (size - 1.0);
  agreement.chance_share = chance / (static_cast<double>(count) * static_cast<double>(count - 1));
  agreement.rank_correlation = stats::spearman(on_map, on_body);
  return agreement;
}

}  // namespace tactile
