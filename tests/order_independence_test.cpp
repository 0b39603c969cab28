// Every technique that claims to be exact gives the same image, within its
// tolerance, whatever order the triangles arrive in (reversed, shuffled,
// whole objects shuffled) and from frame to frame; unsorted visibly moves.
// The reference is cross-checked against uncapped depth peeling.
#include <gtest/gtest.h>

#include "harness/app/check_order.h"
#include "tests/gl_fixture.h"

namespace oit {
namespace {

// The technique is check_order's to set.
RunSpec base(const std::string& scene, const RawParams& scene_params, int size) {
  return test::one_frame("", {}, scene, scene_params, size);
}

void expect_exact_techniques_order_independent(const RunSpec& spec) {
  size_t checked = 0;
  for (const auto& technique : builtin_techniques().all()) {
    const OrderCheck c = check_order(test::harness(), technique, spec, 1);
    if (c.status == "skipped") continue;
    ASSERT_EQ(c.status, "ok") << technique.id << ": " << c.message;
    EXPECT_EQ(c.repeat_difference, 0.0) << technique.id << " flickers between identical frames";
    if (c.exact) {
      ++checked;
      EXPECT_LE(c.largest_difference, technique.exact_tolerance)
          << technique.id << " moved under " << c.worst_order << " on " << spec.scene;
    }
    if (technique.id == "unsorted") {
      EXPECT_GT(c.largest_difference, 0.05) << "unsorted should depend on the order";
    }
  }
  EXPECT_GE(checked, 2u);
}

TEST(OrderIndependence, ExactTechniquesOnStackedQuads) {
  expect_exact_techniques_order_independent(base("quads", {{"layers", "32"}}, 32));
}

TEST(OrderIndependence, ExactTechniquesOnOverlappingSpheres) {
  expect_exact_techniques_order_independent(base("spheres", {}, 48));
}

TEST(OrderIndependence, ReferenceAgreesWithUncappedDepthPeelingOnMeshes) {
  for (const char* scene : {"spheres", "torus", "nested_spheres"}) {
    RunSpec spec = base(scene, {}, 48);
    spec.technique = "depth_peeling";
    const RunResult peeled = test::harness().run(spec);
    ASSERT_EQ(peeled.status, RunStatus::ok) << peeled.message;
    EXPECT_EQ(peeled.counters.fragments_dropped, 0u);
    EXPECT_LE(peeled.error->max_abs, 1e-5) << scene;
  }
}

}  // namespace
}  // namespace oit
