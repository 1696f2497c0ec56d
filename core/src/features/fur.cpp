#include "tactile/features/fur.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "tactile/dsp/fur_preprocess.h"
#include "tactile/error.h"
#include "tactile/signal/taxel_values.h"
#include "tactile/stats/statistics.h"

namespace tactile {

//---- Segment features (spec §3.5) -------------------------------------------------------

FurSeries fur_series(const Eigen::MatrixXd& values, const std::vector<double>& sizes,
                     const std::vector<Point2>& positions, double threshold) {
  const Eigen::Index cells = values.cols();
  if (static_cast<Eigen::Index>(sizes.size()) != cells ||
      static_cast<Eigen::Index>(positions.size()) != cells)
    throw Error("fur features", std::to_string(cells) + " cells but " +
                                    std::to_string(sizes.size()) + " sizes and " +
                                    std::to_string(positions.size()) + " positions");
  const Eigen::Map<const Eigen::ArrayXd> size(sizes.data(), cells);
  Eigen::ArrayXd x(cells), y(cells);
  for (Eigen::Index c = 0; c < cells; ++c) {
    x[c] = positions[c].x;
    y[c] = positions[c].y;
  }
  FurSeries series;
  for (Eigen::Index t = 0; t < values.rows(); ++t) {
    const Eigen::ArrayXd v = values.row(t).transpose().array();
    const Eigen::ArrayXd active = (v > threshold).cast<double>();
    // Müller et al. §3.5: A(t) = Σ s_c act_c, S(t) = Σ v_c, P(t) = max v_c.
    series.area.push_back((size * active).sum());
    series.sum.push_back(v.sum());
    series.peak.push_back(cells > 0 ? v.maxCoeff() : 0.0);
    // Centre weighted by pressure and size over the active cells: w_c = v_c s_c act_c.
    const Eigen::ArrayXd weight = v * size * active;
    const double total = weight.sum();
    if (total > 0.0)
      series.centre.push_back({(weight * x).sum() / total, (weight * y).sum() / total});
  }
  return series;
}

std::array<double, kFurFeatureCount> fur_segment_features(const Eigen::MatrixXd& values,
                                                          const std::vector<double>& sizes,
                                                          const std::vector<Point2>& positions,
                                                          double threshold) {
  const FurSeries series = fur_series(values, sizes, positions, threshold);
  const auto maximum = [](const std::vector<double>& x) {
    return x.empty() ? 0.0 : *std::max_element(x.begin(), x.end());
  };
  std::vector<double> centre_x, centre_y;
  for (const Point2& centre : series.centre) {
    centre_x.push_back(centre.x);
    centre_y.push_back(centre.y);
  }
  // Translation: distance from the first to the last valid centre (0 with fewer than two).
  const double translation = series.centre.size() < 2
                                 ? 0.0
                                 : std::hypot(series.centre.back().x - series.centre.front().x,
                                              series.centre.back().y - series.centre.front().y);
  return {static_cast<double>(values.rows()), stats::mean(series.area),  maximum(series.area),
          stats::variance(series.area),       maximum(series.sum),       stats::mean(series.sum),
          stats::variance(series.sum),        maximum(series.peak),      stats::mean(series.peak),
          stats::variance(series.peak),       stats::mean(centre_x),     stats::mean(centre_y),
          stats::variance(centre_x),          stats::variance(centre_y), translation};
}

//---- The extractor ------------------------------------------------------------------------

namespace {

const std::array<FeatureColumn, kFurFeatureCount> kColumns = {{
    {"duration", "segment length T [samples] (paper 002 feature 1)"},
    {"area_mean", "mean over t of active area A(t) = sum of sizes of cells above threshold [cm^2]"},
    {"area_max", "max over t of active area A(t) [cm^2]"},
    {"area_variance", "population variance over t of active area A(t) [cm^4]"},
    {"sum_pressure_max", "max over t of S(t) = sum of normalised cell pressures"},
    {"sum_pressure_mean", "mean over t of S(t)"},
    {"sum_pressure_variance", "population variance over t of S(t)"},
    {"peak_pressure_max", "max over t of P(t) = pressure of the most excited cell [0-1]"},
    {"peak_pressure_mean", "mean over t of P(t)"},
    {"peak_pressure_variance", "population variance over t of P(t)"},
    {"centre_x", "mean x of the pressure- and size-weighted centre of active cells [cm, map x]"},
    {"centre_y", "mean y of that centre [cm, map y, downwards]"},
    {"centre_x_variance", "population variance of the centre's x over valid samples [cm^2]"},
    {"centre_y_variance", "population variance of the centre's y over valid samples [cm^2]"},
    {"translation", "distance from the first to the last valid centre [cm]"},
}};

class FurExtractor : public FeatureExtractor {
 public:
  explicit FurExtractor(const Parameters& parameters) {
    std::vector<std::string> known = dsp::fur_preprocess_keys();
    known.insert(known.end(), {"threshold", "fur_features"});
    parameters.expect_only(known);
    preprocess_options_ = dsp::fur_preprocess_options(parameters);
    threshold_ = parameters.number("threshold", threshold_);
    if (!(threshold_ >= 0.0 && threshold_ < 1.0))
      throw Error(parameters.where(), "threshold must lie in [0, 1) (values are normalised)");
    const int64_t features = parameters.integer("fur_features", kFurFeatureCount);
    if (features != 14 && features != 15)
      throw Error(parameters.where(),
                  "fur_features=" + std::to_string(features) + ": expected 14 or 15");
    joint_centre_variance_ = features == 14;
  }

  std::string name() const override { return "fur"; }
  std::string description() const override {
    return "Smart fur (paper 002): duration, active area, sum and peak pressure (max, mean, "
           "variance), "
           "pressure centre and its variance, translation, on calibrated [0, 1] pressures";
  }

  std::vector<FeatureColumn> columns(const SkinLayout&) const override {
    std::vector<FeatureColumn> columns(kColumns.begin(), kColumns.end());
    if (joint_centre_variance_) {
      columns[12] = {"centre_variance",
                     "var(centre x) + var(centre y) [cm^2] (the paper's 14-feature list)"};
      columns.erase(columns.begin() + 13);
    }
    return columns;
  }

  Recording preprocess(const Recording& recording, const SkinLayout& layout) const override {
    return dsp::fur_preprocess(recording, layout, preprocess_options_);
  }

  FeatureResult extract(const SegmentInput& input) const override {
    const Stream& stream = dsp::fur_stream(input.recording);
    const auto [begin, end] = sample_range(stream, input.segment.t0, input.segment.t1);
    if (begin >= end) return FeatureResult::skip("segment holds no sample");

    // Every cell of the layout that the stream carries, in cm and cm² (the map is in mm).
    const std::vector<int> columns = taxel_columns(input.layout, stream.channels, 0);
    std::vector<int> used;
    std::vector<double> sizes;
    std::vector<Point2> positions;
    for (size_t k = 0; k < input.layout.taxels.size(); ++k) {
      if (columns[k] < 0) continue;
      const Taxel& taxel = input.layout.taxels[k];
      used.push_back(columns[k]);
      sizes.push_back(taxel.area / 100.0);
      positions.push_back({taxel.position.x / 10.0, taxel.position.y / 10.0});
    }
    if (used.empty())
      return FeatureResult::skip("the stream carries no cell of layout " + input.layout.id);

    Eigen::MatrixXd values(end - begin, static_cast<Eigen::Index>(used.size()));
    for (size_t c = 0; c < used.size(); ++c)
      for (int64_t t = begin; t < end; ++t) {
        const float value = stream.samples(t, used[c]);
        if (!std::isfinite(value))
          return FeatureResult::skip("missing sample (NaN) at sample " + std::to_string(t) +
                                     " of channel " + stream.channels[used[c]]);
        values(t - begin, static_cast<Eigen::Index>(c)) = value;
      }
    const std::array<double, kFurFeatureCount> features =
        fur_segment_features(values, sizes, positions, threshold_);
    FeatureResult result;
    result.values.assign(features.begin(), features.end());
    if (joint_centre_variance_) {
      result.values[12] += result.values[13];
      result.values.erase(result.values.begin() + 13);
    }
    return result;
  }

 private:
  dsp::FurPreprocessOptions preprocess_options_;
  double threshold_ = 0.1;
  bool joint_centre_variance_ = false;
};

}  // namespace

std::unique_ptr<FeatureExtractor> make_fur_extractor(const Parameters& parameters) {
  return std::make_unique<FurExtractor>(parameters);
}

}  // namespace tactile
