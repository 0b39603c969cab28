// The optional window path: a GLFW window (under Xvfb in CI, where Mesa
// gives it llvmpipe) runs the same harness and gets the exact reference.
// Registered in tests/CMakeLists.txt to run under `xvfb-run -a`.
#include <gtest/gtest.h>

#include "harness/run/runner.h"
#include "harness/gl/glfw_window.h"
#include "scenes/stacked_quads.h"
#include "tests/gl_fixture.h"

namespace oit {
namespace {

TEST(GlfwWindow, HarnessRendersTheExactReferenceInAWindowContext) {
  GlfwWindowContext window(64, 64, "oitbench test");
  EXPECT_FALSE(window.device().renderer.empty());
  EXPECT_EQ(window.device().platform, "glfw");
  Harness harness(window, builtin_techniques());
  const RunResult r = harness.run(test::one_frame("reference", {}, "quads", {{"layers", "8"}}, 32));
  ASSERT_EQ(r.status, RunStatus::ok) << r.message;
  StackedQuadsParams p;
  p.layers = 8;
  const glm::vec4 expected = stacked_quads_closed_form(p, glm::vec3(0.0f));
  for (int c = 0; c < 4; ++c) EXPECT_EQ(r.image.at(16, 16, c), expected[c]);
  window.swap_buffers_and_poll();
  EXPECT_FALSE(window.should_close());
}

}  // namespace
}  // namespace oit
