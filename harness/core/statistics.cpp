#include "harness/core/statistics.h"

#include <gsl/gsl_statistics_double.h>

#include <algorithm>

namespace oit {

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
  return s;
}

}  // namespace oit
