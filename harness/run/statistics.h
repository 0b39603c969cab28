#pragma once
// The statistics of timed frames: order statistics and the distribution-free
// interval of the median (binomial order statistics, GSL's binomial CDF),
// the precision a run stops at, drift and outlying frames. One place, so that
// the bench, pareto, the summary and the CSV agree on every figure.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace oit {

// The interval [low, high] of the median and the confidence it reaches
// (below the asked-for one when there are too few samples for it: with n
// samples [min, max] covers the median with 1 - 2 * 0.5^n).
struct MedianInterval {
  double low = 0.0, high = 0.0;
  double confidence = 0.0;
};
// Distribution-free: [x_(l), x_(n-l+1)] for the largest l with
// 2 P(Binomial(n, 1/2) <= l - 1) <= 1 - confidence.
MedianInterval median_interval(std::vector<double> samples, double confidence = 0.95);

struct Summary {
  double median = 0.0, min = 0.0, p05 = 0.0, p95 = 0.0, mean = 0.0;
  MedianInterval interval;  // 95% interval of the median
  std::size_t count = 0;
  // Half the interval's width over the median (infinity for a zero median).
  double relative_half_width() const;
};

// Order statistics (GSL's quantile_from_sorted_data, linear interpolation)
// and the median's 95% interval.
Summary summarize(std::vector<double> samples);

// Whether `summary` pins its median to within +-precision (relative) with
// 95% confidence: the interval reaches 95% and its half-width is at most
// precision x median.
bool precision_reached(const Summary& summary, double precision);

// What a run's frames say against trusting its median, one sentence each:
// drift (the first third's median and the last third's, with their 95%
// intervals apart: at least 18 frames) and outlying frames (beyond Tukey's
// far-out fences, 3 IQR from the quartiles: at least 8 frames). `samples`
// in frame order.
std::vector<std::string> frame_warnings(const std::vector<double>& samples);

// The ratio of two configurations run in interleaved rounds: the median of
// the per-round ratios of their medians and its 95% interval (paired by round).
struct RatioEstimate {
  double ratio = 0.0;
  MedianInterval interval;
  std::size_t rounds = 0;
};
// `numerator` and `denominator`: the per-frame samples of each round, by
// round; rounds where either has no frame are left out. nullopt when no round
// has both.
std::optional<RatioEstimate> paired_round_ratio(const std::vector<std::vector<double>>& numerator,
                                                const std::vector<std::vector<double>>& denominator);

}  // namespace oit
