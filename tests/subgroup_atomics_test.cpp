// shaders/subgroup_atomics.glsl: the shared counters of the list and
// k-buffer techniques bumped once per subgroup (GL_ARB_shader_ballot) must
// give exactly what one atomic per fragment gives: the same node indices'
// count, the same dropped counts, the same overflow retries and the same
// image. Each case runs with the path on (default where the driver has it)
// and with OIT_SHADER_BALLOT=off, in one process.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "harness/gl/shader_capabilities.h"
#include "tests/gl_fixture.h"

namespace oit {
namespace {

struct Case {
  std::string technique;
  RawParams params;
  std::string scene;
  RawParams scene_params;
};

RunResult run_with_ballot(const Case& c, bool ballot) {
  if (ballot) {
    unsetenv("OIT_SHADER_BALLOT");
  } else {
    setenv("OIT_SHADER_BALLOT", "off", 1);
  }
  RunResult result = test::render_once(c.technique, c.params, c.scene, c.scene_params, 64, 48);
  unsetenv("OIT_SHADER_BALLOT");
  return result;
}

void expect_same_with_and_without_ballot(const Case& c) {
  const RunResult on = run_with_ballot(c, true);
  const RunResult off = run_with_ballot(c, false);
  const std::string what = c.technique + " on " + c.scene;
  EXPECT_EQ(on.counters.fragments_stored, off.counters.fragments_stored) << what;
  EXPECT_EQ(on.counters.fragments_dropped, off.counters.fragments_dropped) << what;
  EXPECT_EQ(on.counters.overflow_retries, off.counters.overflow_retries) << what;
  EXPECT_EQ(on.counters.bytes_allocated, off.counters.bytes_allocated) << what;
  EXPECT_EQ(on.image.rgba, off.image.rgba) << what;
}

TEST(SubgroupAtomics, SoftwareGlTakesTheSubgroupPath) {
  // Mesa llvmpipe (the CI device) has GL_ARB_shader_ballot: the fast path is
  // what CI tests and what the README's numbers measured.
  const DeviceProfile& device = test::gl_context().device();
  unsetenv("OIT_SHADER_BALLOT");
  if (device.software) {
    EXPECT_EQ(atomics_path(), "subgroup atomics") << device.renderer;
  }
  setenv("OIT_SHADER_BALLOT", "off", 1);
  EXPECT_EQ(atomics_path(), "plain atomics");
  EXPECT_TRUE(capability_defines().empty());
  unsetenv("OIT_SHADER_BALLOT");
}

TEST(SubgroupAtomics, LinkedListCountsDropsAndRegrowsAlike) {
  // 32 layers, 8 kept: 24 dropped per pixel; a 1-node-per-pixel first pool
  // overflows and grows.
  const Case c{"linked_list", {{"max_per_pixel", "8"}, {"initial_nodes_per_pixel", "1"}}, "quads", {}};
  expect_same_with_and_without_ballot(c);
  const RunResult on = run_with_ballot(c, true);
  EXPECT_EQ(on.counters.fragments_dropped, uint64_t(64 * 48 * 24));
  EXPECT_EQ(on.counters.fragments_stored, uint64_t(64 * 48 * 8));
  EXPECT_EQ(on.counters.overflow_retries, 1u);
  // What is missing is bounded by the transmittance after the nearest 8 layers (alpha 0.3).
  EXPECT_LE(on.error->max_abs, std::pow(0.7, 8) + 1e-5) << "the nearest 8 of 32 layers";
}

TEST(SubgroupAtomics, LinkedListCountingPassSizesTheSamePool) {
  expect_same_with_and_without_ballot({"linked_list", {{"pool_sizing", "count"}}, "spheres", {}});
}

TEST(SubgroupAtomics, IllustrationBufferAndReferenceAlike) {
  expect_same_with_and_without_ballot(
      {"illustration_buffer", {{"max_per_pixel", "4"}, {"initial_nodes_per_pixel", "1"}}, "spheres", {}});
  expect_same_with_and_without_ballot({"reference", {{"initial_nodes_per_pixel", "1"}}, "quads", {{"layers", "8"}}});
}

TEST(SubgroupAtomics, KBufferDropCountsAlike) {
  const Case kbuffer{"kbuffer", {{"k", "4"}}, "quads", {{"layers", "8"}}};
  expect_same_with_and_without_ballot(kbuffer);
  EXPECT_EQ(run_with_ballot(kbuffer, true).counters.fragments_dropped, uint64_t(64 * 48 * 4));
  expect_same_with_and_without_ballot({"bucketed_kbuffer", {{"k", "4"}}, "quads", {{"layers", "8"}}});
  EXPECT_EQ(run_with_ballot({"bucketed_kbuffer", {{"k", "4"}}, "quads", {{"layers", "8"}}}, true)
                .counters.fragments_dropped,
            uint64_t(64 * 48 * 4));
}

TEST(SubgroupAtomics, CappedPeelingCountsWhatItLeavesAlike) {
  // 8 layers, too few passes for either: both leave fragments, and count them.
  const Case depth{"depth_peeling", {{"max_passes", "4"}}, "quads", {{"layers", "8"}}};
  expect_same_with_and_without_ballot(depth);
  EXPECT_GT(run_with_ballot(depth, true).counters.fragments_dropped, 0u);
  const Case dual{"dual_depth_peeling", {{"max_passes", "2"}}, "quads", {{"layers", "8"}}};
  expect_same_with_and_without_ballot(dual);
  EXPECT_GT(run_with_ballot(dual, true).counters.fragments_dropped, 0u);
}

}  // namespace
}  // namespace oit
