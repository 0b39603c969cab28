#include "gl_fixture.h"

#include <gtest/gtest.h>

namespace oit::test {

GlContext& gl_context() {
  static std::unique_ptr<GlContext> context = create_headless_context();
  return *context;
}

Harness& harness() {
  static Harness instance(gl_context(), builtin_techniques());
  return instance;
}

RunResult render_once(const std::string& technique, const RawParams& params, const std::string& scene,
                      const RawParams& scene_params, int width, int height) {
  RunSpec spec;
  spec.technique = technique;
  spec.params = params;
  spec.scene = scene;
  spec.scene_params = scene_params;
  spec.width = width;
  spec.height = height;
  spec.warmup = 0;
  spec.frames = 1;
  RunResult result = harness().run(spec);
  EXPECT_EQ(result.status, RunStatus::ok) << technique << ": " << result.message;
  return result;
}

}  // namespace oit::test
