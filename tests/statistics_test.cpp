// Order statistics of per-frame samples (what every CSV row reports).
#include <gtest/gtest.h>

#include "harness/run/statistics.h"

namespace oit {
namespace {

TEST(Statistics, OddCountMedianIsTheMiddleSample) {
  const Summary s = summarize({5.0, 1.0, 3.0});
  EXPECT_EQ(s.count, 3u);
  EXPECT_DOUBLE_EQ(s.median, 3.0);
  EXPECT_DOUBLE_EQ(s.min, 1.0);
  EXPECT_DOUBLE_EQ(s.mean, 3.0);
}

TEST(Statistics, EvenCountMedianInterpolates) {
  EXPECT_DOUBLE_EQ(summarize({4.0, 1.0, 2.0, 3.0}).median, 2.5);
}

TEST(Statistics, PercentilesInterpolateLinearly) {
  std::vector<double> samples;
  for (int i = 0; i <= 100; ++i) samples.push_back(double(100 - i));  // 0..100, unsorted
  const Summary s = summarize(samples);
  EXPECT_DOUBLE_EQ(s.p05, 5.0);
  EXPECT_DOUBLE_EQ(s.p95, 95.0);
  EXPECT_DOUBLE_EQ(s.median, 50.0);
  EXPECT_DOUBLE_EQ(s.min, 0.0);
}

TEST(Statistics, OneOutlierMovesTheMeanNotTheMedian) {
  const Summary s = summarize({10.0, 10.0, 10.0, 10.0, 1000.0});
  EXPECT_DOUBLE_EQ(s.median, 10.0);
  EXPECT_DOUBLE_EQ(s.mean, 208.0);
}

TEST(Statistics, EmptyIsAllZero) {
  const Summary s = summarize({});
  EXPECT_EQ(s.count, 0u);
  EXPECT_EQ(s.median, 0.0);
}

}  // namespace
}  // namespace oit
