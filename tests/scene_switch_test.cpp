// A technique instance outlives the scenes it renders (the viewer loads one
// scene after another under a running technique) and keeps per-scene data
// between frames: triangle tables, bounds, checked limits. A later scene can
// be built at the address of an earlier one, so that data must be keyed by
// something no later scene can share (SceneGpu::serial), never by address.
#include <gtest/gtest.h>

#include <optional>

#include "tests/gl_fixture.h"
#include "scenes/scene_library.h"

namespace oit {
namespace {

constexpr int kSize = 48;

// One instance of a technique with defaults, rendering into its own target.
struct Renderer {
  std::unique_ptr<Technique> technique;
  RenderTarget target{kSize, kSize};
  StageClock clock{ClockKind::wall};
  explicit Renderer(const TechniqueDescriptor& descriptor) {
    technique = descriptor.create(ParamSet(descriptor.params, {}, descriptor.id));
    technique->resize(kSize, kSize);
  }
  Image render(const SceneGpu& gpu) {
    const Scene& scene = gpu.scene();
    const Frame frame{gpu,  scene.camera.view, scene.camera.projection(1.0f), kSize, kSize, glm::vec3(0.0f),
                      target.framebuffer.id(), clock};
    render_frame(*technique, frame, false);
    return read_texture_rgba32f(target.color.id(), kSize, kSize);
  }
};

TEST(EveryTechnique, ASceneBuiltWhereAnEarlierOneLivedRendersAsInAFreshInstance) {
  test::gl_context();
  for (const TechniqueDescriptor& descriptor : builtin_techniques().all()) {
    SCOPED_TRACE(descriptor.id);
    Renderer reused(descriptor), fresh(descriptor);
    // std::optional builds each scene in the same storage: the second torus
    // and its upload sit at the first one's addresses.
    std::optional<Scene> scene(load_scene("torus", {}));
    std::optional<SceneGpu> gpu(std::in_place, *scene);
    reused.render(*gpu);
    const Scene* first_address = &*scene;
    gpu.reset();
    scene.reset();
    scene.emplace(load_scene("spheres", {}));
    gpu.emplace(*scene);
    ASSERT_EQ(&*scene, first_address);
    const Image second = reused.render(*gpu);
    EXPECT_EQ(compare_images(second, fresh.render(*gpu)).max_abs, 0.0);
  }
}

}  // namespace
}  // namespace oit
