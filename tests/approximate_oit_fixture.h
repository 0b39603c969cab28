#pragma once
// What the tests of the approximate techniques (moment_oit,
// hybrid_transparency, stochastic_transparency, weighted_blended, ...)
// share: one untimed frame of a configuration, and checks on its image.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "harness/app/check_order.h"
#include "tests/gl_fixture.h"
#include "harness/gl/shader_capabilities.h"

namespace oit::test {

// Channel values that are not finite or lie outside [0, 1] (the stress
// suite's garbage test, with the same float margins).
inline size_t garbage_values(const Image& image) {
  size_t garbage = 0;
  for (float v : image.rgba) garbage += !(std::isfinite(v) && v >= -1e-4f && v <= 1.0f + 1e-3f);
  return garbage;
}

// The RMSE against the reference of one run per value of `knob` (the other
// parameters as in `params`), in the order given.
inline std::vector<double> rmse_per_value(const std::string& technique, RawParams params, const std::string& knob,
                                          const std::vector<std::string>& values, const std::string& scene,
                                          const RawParams& scene_params, int size) {
  std::vector<double> errors;
  for (const std::string& value : values) {
    params[knob] = value;
    const RunResult r = run_ok(one_frame(technique, params, scene, scene_params, size));
    errors.push_back(r.error ? r.error->rmse : -1.0);
  }
  return errors;
}

// One quad layer (no fragment in front of another) with each of `values`
// of `knob`: within `float_bound` of the reference with float storage and
// within `half_bound` with precision=half; the bounds are the storage's
// rounding, which the tests derive.
inline void expect_single_layer_within_storage_precision(const OneFrameOf& spec_of, const std::string& knob,
                                                          const std::vector<std::string>& values, double float_bound,
                                                          double half_bound) {
  for (const std::string& value : values) {
    const RunResult full = run_ok(spec_of({{knob, value}}, "quads", {{"layers", "1"}}));
    ASSERT_TRUE(full.error.has_value());
    EXPECT_LT(full.error->max_abs, float_bound) << value;
    const RunResult half = run_ok(spec_of({{knob, value}, {"precision", "half"}}, "quads", {{"layers", "1"}}));
    ASSERT_TRUE(half.error.has_value());
    EXPECT_LT(half.error->max_abs, half_bound) << value;
  }
}

// Each value strictly below the one before it.
inline void expect_falling(const std::vector<double>& errors, const std::string& what) {
  for (size_t i = 1; i < errors.size(); ++i)
    EXPECT_LT(errors[i], errors[i - 1]) << what << ": step " << i << " of " << ::testing::PrintToString(errors);
}

// The techniques with ordered per-pixel access (multi_layer_alpha_blending,
// adaptive_transparency): no fragment may miss its critical section. With
// the spin-lock fallback that is the claim of the README's proof for
// llvmpipe, checked on every run; with interlock there is no lock at all.
inline void expect_no_lock_failures(const RunResult& r) {
  EXPECT_EQ(extra_counter(r, "lock_failures"), 0.0) << r.spec.technique << " on " << r.spec.scene;
  EXPECT_EQ(r.counters.fragments_dropped, 0u);
  EXPECT_EQ(extra_counter(r, "interlock"), ordered_access_extension().empty() ? 0.0 : 1.0);
}

// One frame of a technique with ordered per-pixel access, which must be
// `ok` and have lost no fragment to its lock.
inline RunResult run_ordered(const RunSpec& spec) {
  RunResult r = run_ok(spec);
  expect_no_lock_failures(r);
  return r;
}

// `oitbench check-order`'s verdict for one technique and parameter set on
// `scene` (original order twice, reversed, shuffled:1, objects_shuffled:1).
inline OrderCheck order_check(const std::string& technique, const RawParams& params, const std::string& scene,
                              const RawParams& scene_params, int size) {
  RunSpec spec = one_frame(technique, params, scene, scene_params, size);
  return check_order(harness(), builtin_techniques().get(technique), spec, 1);
}

}  // namespace oit::test
