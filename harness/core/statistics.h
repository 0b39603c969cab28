#pragma once
#include <cstddef>
#include <vector>

namespace oit {

struct Summary {
  double median = 0.0, min = 0.0, p05 = 0.0, p95 = 0.0, mean = 0.0;
  std::size_t count = 0;
};

// Order statistics (GSL's quantile_from_sorted_data, linear interpolation).
Summary summarize(std::vector<double> samples);

}  // namespace oit
