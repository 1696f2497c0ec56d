#pragma once
// Shared building blocks of every feature set (spec §0 and §6.1-6.3): descriptive
// statistics, ranks and correlation, implemented once. All in double precision.

#include <Eigen/Core>
#include <span>
#include <vector>

namespace tactile::stats {

// (1/T) Σ x; 0 for an empty input.
double mean(std::span<const double> x);
// Population variance (1/T) Σ (x - mean)²; 0 for T = 0.
double variance(std::span<const double> x);
// The middle value, the mean of the two middle values for an even count; 0 for no values.
double median(std::vector<double> values);
float median(std::vector<float> values);
// The value sorting would put at `index` (0-based, below values.size()), found in linear time
// (std::nth_element); reorders `values`. A quantile picks its index by its own rounding.
double nth_smallest(std::span<double> values, size_t index);
float nth_smallest(std::span<float> values, size_t index);
// Sample standard deviation with 1/(T-1); 0 for T <= 1.
double sample_std(std::span<const double> x);
// x[t+1] - x[t], length T-1 (empty for T < 2).
std::vector<double> diff(std::span<const double> x);
// Spec §0 zero test: v <= 1e-12 * max(1, mean(x²)).
bool is_zero_variance(double variance_value, std::span<const double> x);
// Index of the first maximum / minimum; -1 for an empty input.
int64_t argmax(std::span<const double> x);
int64_t argmin(std::span<const double> x);

// 1-based ranks, ties get the average of the ranks they span (spec §6.2).
std::vector<double> rank(std::span<const double> x);
// Pearson correlation (spec §6.3); 0 when T < 2 or either variance is zero.
double pearson(std::span<const double> x, std::span<const double> y);
// Spearman = Pearson of average ranks (Kaboli §1.6 recommended form).
double spearman(std::span<const double> x, std::span<const double> y);
// Kaboli eq. (6) as printed: 1 - 6 Σ R² / (N (N² - 1)), exact only without ties.
double spearman_eq6(std::span<const double> x, std::span<const double> y);

struct Hjorth {
  double activity = 0.0;
  double mobility = 0.0;
  double complexity = 0.0;
};
// Kaboli eqs. (2)-(4): Act = var(x), Mob = sqrt(var(dx) / var(x)), Comp = Mob(dx) / Mob(x),
// with first differences not divided by dt; zero denominators give 0 (spec §1.4).
Hjorth hjorth(std::span<const double> x);

// A column of a float sample matrix as doubles (features are computed in double).
std::vector<double> to_double(const float* values, int64_t count);

}  // namespace tactile::stats
