#include "tactile/stats/statistics.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace tactile::stats {

double mean(std::span<const double> x) {
  if (x.empty()) return 0.0;
  return std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(x.size());
}

namespace {

template <typename Value>
Value nth_smallest_of(std::span<Value> values, size_t index) {
  const auto at = values.begin() + static_cast<std::ptrdiff_t>(index);
  std::nth_element(values.begin(), at, values.end());
  return *at;
}

template <typename Value>
Value median_of(std::vector<Value> values) {
  if (values.empty()) return Value(0);
  const size_t middle = values.size() / 2;
  const Value upper = nth_smallest_of(std::span<Value>(values), middle);
  if (values.size() % 2 == 1) return upper;
  // nth_element leaves the smaller half before the middle: its largest is the lower middle.
  const Value lower =
      *std::max_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(middle));
  return Value(0.5) * (lower + upper);
}

}  // namespace

double median(std::vector<double> values) { return median_of(std::move(values)); }
float median(std::vector<float> values) { return median_of(std::move(values)); }

double nth_smallest(std::span<double> values, size_t index) {
  return nth_smallest_of(values, index);
}
float nth_smallest(std::span<float> values, size_t index) { return nth_smallest_of(values, index); }

double variance(std::span<const double> x) {
  if (x.empty()) return 0.0;
  const double average = mean(x);
  double sum = 0.0;
  for (double value : x) sum += (value - average) * (value - average);
  return sum / static_cast<double>(x.size());
}

double sample_std(std::span<const double> x) {
  if (x.size() <= 1) return 0.0;
  const double n = static_cast<double>(x.size());
  return std::sqrt(variance(x) * n / (n - 1.0));
}

std::vector<double> diff(std::span<const double> x) {
  std::vector<double> out;
  if (x.size() < 2) return out;
  out.resize(x.size() - 1);
  for (size_t t = 0; t + 1 < x.size(); ++t) out[t] = x[t + 1] - x[t];
  return out;
}

bool is_zero_variance(double variance_value, std::span<const double> x) {
  double mean_square = 0.0;
  for (double value : x) mean_square += value * value;
  if (!x.empty()) mean_square /= static_cast<double>(x.size());
  return variance_value <= 1e-12 * std::max(1.0, mean_square);
}

int64_t argmax(std::span<const double> x) {
  if (x.empty()) return -1;
  return std::max_element(x.begin(), x.end()) - x.begin();  // first of equal maxima
}

int64_t argmin(std::span<const double> x) {
  if (x.empty()) return -1;
  return std::min_element(x.begin(), x.end()) - x.begin();
}

std::vector<double> rank(std::span<const double> x) {
  std::vector<size_t> order(x.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return x[a] < x[b]; });
  std::vector<double> ranks(x.size());
  for (size_t start = 0; start < order.size();) {
    size_t end = start + 1;
    while (end < order.size() && x[order[end]] == x[order[start]]) ++end;
    // Positions start..end-1 hold equal values: each gets the mean of ranks start+1..end.
    const double shared = 0.5 * static_cast<double>(start + 1 + end);
    for (size_t k = start; k < end; ++k) ranks[order[k]] = shared;
    start = end;
  }
  return ranks;
}

double pearson(std::span<const double> x, std::span<const double> y) {
  const size_t n = std::min(x.size(), y.size());
  if (n < 2) return 0.0;
  const double mean_x = mean(x.first(n));
  const double mean_y = mean(y.first(n));
  double sxy = 0.0, sxx = 0.0, syy = 0.0;
  for (size_t t = 0; t < n; ++t) {
    const double dx = x[t] - mean_x;
    const double dy = y[t] - mean_y;
    sxy += dx * dy;
    sxx += dx * dx;
    syy += dy * dy;
  }
  if (is_zero_variance(sxx / n, x.first(n)) || is_zero_variance(syy / n, y.first(n))) return 0.0;
  return sxy / (std::sqrt(sxx) * std::sqrt(syy));
}

double spearman(std::span<const double> x, std::span<const double> y) {
  const size_t n = std::min(x.size(), y.size());
  const std::vector<double> rank_x = rank(x.first(n));
  const std::vector<double> rank_y = rank(y.first(n));
  return pearson(rank_x, rank_y);
}

double spearman_eq6(std::span<const double> x, std::span<const double> y) {
  const size_t n = std::min(x.size(), y.size());
  if (n < 2) return 0.0;
  const std::vector<double> rank_x = rank(x.first(n));
  const std::vector<double> rank_y = rank(y.first(n));
  double sum = 0.0;
  for (size_t t = 0; t < n; ++t) sum += (rank_x[t] - rank_y[t]) * (rank_x[t] - rank_y[t]);
  const double count = static_cast<double>(n);
  return 1.0 - 6.0 * sum / (count * (count * count - 1.0));
}

Hjorth hjorth(std::span<const double> x) {
  Hjorth result;
  result.activity = variance(x);
  if (x.size() < 2 || is_zero_variance(result.activity, x)) {
    result.activity = x.size() < 2 ? 0.0 : result.activity;
    return result;
  }
  const std::vector<double> dx = diff(x);
  const double activity_dx = variance(dx);
  result.mobility = std::sqrt(activity_dx / result.activity);
  if (dx.size() < 2 || is_zero_variance(activity_dx, dx)) return result;
  const std::vector<double> ddx = diff(dx);
  const double mobility_dx = std::sqrt(variance(ddx) / activity_dx);
  result.complexity = mobility_dx / result.mobility;
  return result;
}

std::vector<double> to_double(const float* values, int64_t count) {
  return std::vector<double>(values, values + count);
}

}  // namespace tactile::stats
