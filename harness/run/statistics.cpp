#include "harness/run/statistics.h"

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_statistics_double.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace oit {
namespace {

double median_of(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return gsl_stats_median_from_sorted_data(values.data(), 1, values.size());
}

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0) {
  char text[160];
  std::snprintf(text, sizeof text, pattern, a, b, c);
  return text;
}

}  // namespace

MedianInterval median_interval(std::vector<double> samples, double confidence) {
  MedianInterval interval;
  const size_t n = samples.size();
  if (n == 0) return interval;
  std::sort(samples.begin(), samples.end());
  const double alpha = 1.0 - confidence;
  // l (1-based) grows while the interval [x_(l), x_(n-l+1)] still covers the
  // median with the asked-for confidence.
  size_t l = 1;
  while (l + 1 <= (n + 1) / 2 && 2.0 * gsl_cdf_binomial_P(unsigned(l), 0.5, unsigned(n)) <= alpha) ++l;
  interval.low = samples[l - 1];
  interval.high = samples[n - l];
  interval.confidence = l == 1 ? 1.0 - 2.0 * std::pow(0.5, double(n))
                               : 1.0 - 2.0 * gsl_cdf_binomial_P(unsigned(l - 1), 0.5, unsigned(n));
  return interval;
}

double Summary::relative_half_width() const {
  if (median <= 0.0) return std::numeric_limits<double>::infinity();
  return (interval.high - interval.low) / 2.0 / median;
}

Summary summarize(std::vector<double> samples) {
  Summary s;
  s.count = samples.size();
  if (samples.empty()) return s;
  std::sort(samples.begin(), samples.end());
  const double* data = samples.data();
  const size_t n = samples.size();
  s.median = gsl_stats_median_from_sorted_data(data, 1, n);
  s.min = samples.front();
  s.p05 = gsl_stats_quantile_from_sorted_data(data, 1, n, 0.05);
  s.p95 = gsl_stats_quantile_from_sorted_data(data, 1, n, 0.95);
  s.mean = gsl_stats_mean(data, 1, n);
  s.interval = median_interval(std::move(samples));
  return s;
}

bool precision_reached(const Summary& summary, double precision) {
  return summary.count > 0 && summary.interval.confidence >= 0.95 && summary.relative_half_width() <= precision;
}

std::vector<std::string> frame_warnings(const std::vector<double>& samples) {
  std::vector<std::string> warnings;
  const size_t n = samples.size();
  if (n >= 18) {
    const std::vector<double> first(samples.begin(), samples.begin() + long(n / 3));
    const std::vector<double> last(samples.end() - long(n / 3), samples.end());
    const MedianInterval a = median_interval(first), b = median_interval(last);
    if (a.high < b.low || b.high < a.low) {
      const double from = median_of(first), to = median_of(last);
      warnings.push_back(format("drift: the first third's median %.3g ms, the last third's %.3g ms (%+.0f%%)", from,
                                to, (to / from - 1.0) * 100.0));
    }
  }
  if (n >= 8) {
    std::vector<double> sorted = samples;
    std::sort(sorted.begin(), sorted.end());
    const double q1 = gsl_stats_quantile_from_sorted_data(sorted.data(), 1, n, 0.25);
    const double q3 = gsl_stats_quantile_from_sorted_data(sorted.data(), 1, n, 0.75);
    const double low = q1 - 3.0 * (q3 - q1), high = q3 + 3.0 * (q3 - q1);
    const auto outlying = std::count_if(samples.begin(), samples.end(), [&](double v) { return v < low || v > high; });
    if (outlying > 0)
      warnings.push_back(format("%.0f outlying frame(s) beyond [%.3g, %.3g] ms (3 IQR from the quartiles)",
                                double(outlying), std::max(low, 0.0), high));
  }
  return warnings;
}

std::optional<RatioEstimate> paired_round_ratio(const std::vector<std::vector<double>>& numerator,
                                                const std::vector<std::vector<double>>& denominator) {
  std::vector<double> ratios;
  for (size_t r = 0; r < std::min(numerator.size(), denominator.size()); ++r) {
    if (numerator[r].empty() || denominator[r].empty()) continue;
    const double base = median_of(denominator[r]);
    if (base > 0.0) ratios.push_back(median_of(numerator[r]) / base);
  }
  if (ratios.empty()) return std::nullopt;
  RatioEstimate estimate;
  estimate.ratio = median_of(ratios);
  estimate.rounds = ratios.size();
  estimate.interval = median_interval(std::move(ratios));
  return estimate;
}

}  // namespace oit
