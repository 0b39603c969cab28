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

TEST(EveryTechnique, ASceneBuiltWhereAnEarlierOneLivedRendersAsInAFreshInstance) {
  test::gl_context();
  for (const TechniqueDescriptor& descriptor : builtin_techniques().all()) {
    SCOPED_TRACE(descriptor.id);
    test::TechniqueRenderer reused(descriptor, kSize, kSize), fresh(descriptor, kSize, kSize);
    // std::optional builds each scene in the same storage: the spheres and
    // their upload sit at the torus's addresses.
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
