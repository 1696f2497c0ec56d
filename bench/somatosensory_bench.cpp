// The somatosensory map against the body (issue 46, Robovie's Fig. 8): Robovie simulated for 2,
// 10 and 30 minutes (its trials end to end, subject 1), the map made by MDS of -ln|R| over the
// films' signals, and how far it keeps the body: the share of each film's 5 nearest on the map
// that lie on its body part (beside chance), Spearman's correlation of map and body distances,
// and the share of distances no flat map holds. bench/SOMATOSENSORY.md holds a run.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "tactile/layout/skin_layout.h"
#include "tactile/ml/somatosensory.h"
#include "tactile/signal/sample_source.h"
#include "tactile/sim/simulator.h"
#include "tactile/skins/skin.h"

namespace {

// Robovie's trials of one subject end to end until `seconds` are simulated.
tactile::Stream robovie_for(double seconds, const tactile::SkinLayout& layout) {
  tactile::SimulationOptions options;
  options.subjects = 1;
  tactile::Stream whole;
  for (int trial = 0;
       whole.rate_hz == 0.0 || static_cast<double>(whole.samples.rows()) / whole.rate_hz < seconds;
       ++trial) {
    tactile::SimulatedTrial made =
        tactile::skin_record("robovie").simulate(layout, options, 0, trial);
    const tactile::Stream& stream = made.recording.streams.front();
    if (trial == 0) {
      whole = stream;
      continue;
    }
    const auto rows = whole.samples.rows();
    whole.samples.conservativeResize(rows + stream.samples.rows(), Eigen::NoChange);
    whole.samples.bottomRows(stream.samples.rows()) = stream.samples;
  }
  const auto keep = static_cast<Eigen::Index>(seconds * whole.rate_hz);
  whole.samples.conservativeResize(std::min(keep, whole.samples.rows()), Eigen::NoChange);
  return whole;
}

// Left against right (the paper's Fig. 7 reads two hands apart): over the films of parts named
// "...-left" or "...-right", the share of each one's 5 nearest such films on the map that lie on
// the other side, and the share a random placement gives.
struct Sides {
  double other_side = 0.0;
  double at_random = 0.0;
};

Sides left_against_right(const tactile::SomatosensoryMap& map, const tactile::SkinLayout& layout) {
  auto side_of = [](const std::string& part) {
    if (part.ends_with("-left")) return -1;
    if (part.ends_with("-right")) return 1;
    return 0;
  };
  std::vector<size_t> lateral;
  std::vector<int> side;
  for (size_t k = 0; k < map.taxels.size(); ++k) {
    const tactile::Taxel* taxel = layout.find_taxel(map.taxels[k]);
    if (taxel == nullptr || side_of(taxel->body_part) == 0) continue;
    lateral.push_back(k);
    side.push_back(side_of(taxel->body_part));
  }
  const size_t count = lateral.size();
  Sides sides;
  if (count < 7) return sides;
  double other = 0.0;
  std::vector<std::pair<double, size_t>> nearest;
  for (size_t i = 0; i < count; ++i) {
    nearest.clear();
    for (size_t j = 0; j < count; ++j)
      if (j != i)
        nearest.push_back({std::hypot(map.positions[lateral[i]].x - map.positions[lateral[j]].x,
                                      map.positions[lateral[i]].y - map.positions[lateral[j]].y),
                           j});
    std::partial_sort(nearest.begin(), nearest.begin() + 5, nearest.end());
    for (int n = 0; n < 5; ++n) other += side[nearest[static_cast<size_t>(n)].second] != side[i];
  }
  sides.other_side = other / (5.0 * static_cast<double>(count));
  const double left = static_cast<double>(std::count(side.begin(), side.end(), -1));
  const double right = static_cast<double>(count) - left;
  sides.at_random = 2.0 * left * right / (static_cast<double>(count) * (count - 1.0));
  return sides;
}

// The regions the paper's Fig. 12 reads (the head apart; the front of the body, F-body; the
// left and right flanks together), and the back: per region, the share of its films' 5 nearest
// on the map that lie in the region, beside the share a random placement gives.
void print_regions(const tactile::SomatosensoryMap& map, const tactile::SkinLayout& layout) {
  auto region_of = [](const std::string& part) -> std::string {
    if (part == "chest-upper" || part == "chest-lower") return "front of the body (chest)";
    if (part == "side-left" || part == "side-right") return "flanks, left and right";
    if (part == "back-upper" || part == "back-lower") return "back";
    return part;
  };
  std::vector<std::string> region;
  for (int64_t id : map.taxels) {
    const tactile::Taxel* taxel = layout.find_taxel(id);
    region.push_back(taxel ? region_of(taxel->body_part) : std::string());
  }
  std::printf("\nRegions at 30 minutes (share of the 5 nearest in the region, random):\n\n");
  const size_t count = region.size();
  std::vector<std::pair<double, size_t>> nearest;
  for (const char* name : {"head", "front of the body (chest)", "back", "flanks, left and right"}) {
    double share = 0.0;
    size_t films = 0;
    for (size_t i = 0; i < count; ++i) {
      if (region[i] != name) continue;
      ++films;
      nearest.clear();
      for (size_t j = 0; j < count; ++j)
        if (j != i)
          nearest.push_back({std::hypot(map.positions[i].x - map.positions[j].x,
                                        map.positions[i].y - map.positions[j].y),
                             j});
      std::partial_sort(nearest.begin(), nearest.begin() + 5, nearest.end());
      for (int n = 0; n < 5; ++n) share += region[nearest[static_cast<size_t>(n)].second] == name;
    }
    if (films == 0) continue;
    std::printf("- %s (%zu films): %.0f %% (random %.0f %%)\n", name, films,
                100.0 * share / (5.0 * static_cast<double>(films)),
                100.0 * static_cast<double>(films - 1) / static_cast<double>(count - 1));
  }
}

// Why left and right mix: for each part the body has twice ("upper-arm-left" and
// "upper-arm-right"), the median |R| between two films of one side's part and between a film
// of the left part and one of the right.
void print_left_right_correlations(const tactile::SampleSource& source,
                                   const tactile::SkinLayout& layout, int modality) {
  std::vector<int> columns;
  std::vector<std::string> parts;
  for (const tactile::Taxel& taxel : layout.taxels) {
    columns.push_back(taxel.channels[static_cast<size_t>(modality)]);
    parts.push_back(taxel.body_part);
  }
  tactile::CorrelationSums sums(static_cast<int>(columns.size()));
  sums.add(source, columns);
  const Eigen::MatrixXd correlation = sums.correlation();
  auto paired = [](const std::string& part) -> std::string {
    for (const char* side : {"-left", "-right"})
      if (part.ends_with(side)) return part.substr(0, part.size() - std::string(side).size());
    return {};
  };
  std::map<std::string, std::pair<std::vector<double>, std::vector<double>>> pairs;
  for (size_t i = 0; i < parts.size(); ++i)
    for (size_t j = i + 1; j < parts.size(); ++j) {
      const std::string part = paired(parts[i]);
      if (part.empty() || part != paired(parts[j])) continue;
      const double r =
          std::abs(correlation(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)));
      (parts[i] == parts[j] ? pairs[part].first : pairs[part].second).push_back(r);
    }
  auto median = [](std::vector<double> values) {
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    return values[values.size() / 2];
  };
  std::printf(
      "\nMedian |R| at 30 minutes, two films of one side's part / a left and a right film:\n\n");
  for (const auto& [part, both] : pairs)
    if (!both.first.empty() && !both.second.empty())
      std::printf("- %s: %.2f / %.2f\n", part.c_str(), median(both.first), median(both.second));
}

}  // namespace

int main() {
  const tactile::SkinLayout layout = tactile::load_layout("robovie");
  const int modality = std::max(0, layout.modality_index(layout.display_modality));
  std::printf(
      "| minutes | films | same body part, 5 nearest | at random | rank correlation, map vs "
      "body distance | no flat map holds | other side among 5 nearest left/right films (random) "
      "| seconds |\n|---|---|---|---|---|---|---|---|\n");
  for (double minutes : {2.0, 10.0, 30.0}) {
    const auto started = std::chrono::steady_clock::now();
    const tactile::MemorySampleSource source(robovie_for(60.0 * minutes, layout), layout.id,
                                             "robovie");
    const tactile::SomatosensoryMap map = tactile::somatosensory_map(source, layout, modality);
    const tactile::MapBodyAgreement agreement = tactile::map_body_agreement(map, layout);
    const double took =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const Sides sides = left_against_right(map, layout);
    std::printf("| %.0f | %zu | %.0f %% | %.0f %% | %.2f | %.0f %% | %.0f %% (%.0f %%) | %.0f |\n",
                minutes, map.taxels.size(), 100.0 * agreement.same_part_share,
                100.0 * agreement.chance_share, agreement.rank_correlation,
                100.0 * map.negative_eigenvalue_ratio, 100.0 * sides.other_side,
                100.0 * sides.at_random, took);
    std::fflush(stdout);
    if (minutes == 30.0) {
      std::printf("\nPer body part at %.0f minutes (same body part among the 5 nearest):\n\n",
                  minutes);
      for (const auto& [part, share] : agreement.part_share)
        std::printf("- %s: %.0f %%\n", part.c_str(), 100.0 * share);
      print_regions(map, layout);
      print_left_right_correlations(source, layout, modality);
    }
  }
  return 0;
}
