// Programs built for the scene's shading (harness/gl/shader_program.h,
// SceneShading): an unlit scene's programs fetch no normal, images are those
// of the run-time branch on u_lit, a lit scene is lit after an unlit one in
// the same process, and a program built for the other shading is refused.
#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>

#include "harness/gl/shader_program.h"
#include "scenes/scene_library.h"
#include "tests/gl_fixture.h"

namespace oit {
namespace {

constexpr const char* kShadingPass = "algorithms/unsorted/unsorted.frag";  // only oit_shade()

bool has_input(const Program& program, const char* name) {
  return glGetProgramResourceIndex(program.id(), GL_PROGRAM_INPUT, name) != GL_INVALID_INDEX;
}
bool has_uniform(const Program& program, const char* name) {
  return glGetProgramResourceIndex(program.id(), GL_UNIFORM, name) != GL_INVALID_INDEX;
}

Program shading_pass(SceneShading shading) {
  const SceneShadingScope scope(shading);
  return build_geometry_program(kShadingPass);
}

TEST(SceneShading, AnUnlitProgramFetchesNoNormalALitOneDoes) {
  test::gl_context();
  const Program unlit = shading_pass(SceneShading::unlit);
  const Program lit = shading_pass(SceneShading::lit);
  const Program any = shading_pass(SceneShading::any);
  // The linker drops the varyings nothing reads, then the attributes that fed them.
  EXPECT_FALSE(has_input(unlit, "a_normal"));
  EXPECT_TRUE(has_input(lit, "a_normal"));
  EXPECT_TRUE(has_input(any, "a_normal"));  // the run-time branch reads it on every scene
  EXPECT_FALSE(has_uniform(unlit, "u_lit"));
  EXPECT_FALSE(has_uniform(lit, "u_lit"));
  EXPECT_TRUE(has_uniform(any, "u_lit"));
  EXPECT_EQ(scene_shading_of(unlit.id()), SceneShading::unlit);
  EXPECT_EQ(scene_shading_of(lit.id()), SceneShading::lit);
  EXPECT_EQ(scene_shading_of(any.id()), SceneShading::any);
  EXPECT_EQ(current_scene_shading(), SceneShading::any);  // every scope ended
}

TEST(SceneShading, ProgramsThatDoNotShadeAreOneProgramForEveryScene) {
  test::gl_context();
  const std::vector<ShaderStageSource> plain = {{GL_VERTEX_SHADER, "shaders/fullscreen.vert"},
                                                {GL_FRAGMENT_SHADER, "tests/shaders/defined_value.frag"}};
  const std::vector<ShaderStageSource> shading = {{GL_VERTEX_SHADER, "shaders/geometry.vert"},
                                                  {GL_FRAGMENT_SHADER, kShadingPass}};
  auto keys = [&](const std::vector<ShaderStageSource>& stages) {
    std::vector<std::string> result;
    for (SceneShading s : {SceneShading::any, SceneShading::unlit, SceneShading::lit}) {
      const SceneShadingScope scope(s);
      result.push_back(program_cache_key(stages, {{"VALUE", "0.5"}}));
    }
    return result;
  };
  const std::vector<std::string> plain_keys = keys(plain), shading_keys = keys(shading);
  EXPECT_EQ(plain_keys[0], plain_keys[1]);
  EXPECT_EQ(plain_keys[0], plain_keys[2]);
  EXPECT_NE(shading_keys[0], shading_keys[1]);
  EXPECT_NE(shading_keys[1], shading_keys[2]);
  EXPECT_NE(shading_keys[0], shading_keys[2]);
  const SceneShadingScope scope(SceneShading::unlit);
  const Program program = build_fullscreen_program("tests/shaders/defined_value.frag", {{"VALUE", "0.5"}});
  EXPECT_EQ(scene_shading_of(program.id()), SceneShading::any);
  EXPECT_EQ(test::drawn_texel(program).r, 0.5f);
}

TEST(SceneShading, AProgramBuiltForTheOtherShadingIsRefused) {
  test::gl_context();
  const Scene torus = load_scene("torus", {});
  const SceneGpu gpu(torus);
  StageClock clock(ClockKind::wall);
  const Frame frame{gpu, torus.camera.view, torus.camera.projection(1.0f), 8, 8, glm::vec3(0.0f), 0, clock};
  const Program unlit = shading_pass(SceneShading::unlit);
  try {
    frame.set_shared_uniforms(unlit.id());
    FAIL() << "an unlit program was given a lit scene's uniforms";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("was built for unlit scenes but draws lit scene 'torus'"), std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(frame.set_shared_uniforms(shading_pass(SceneShading::lit).id()));
  EXPECT_NO_THROW(frame.set_shared_uniforms(shading_pass(SceneShading::any).id()));
}

// One frame of `technique` created outside any scope: its programs branch on
// u_lit at run time, as every program did before shadings were compiled in.
Image run_time_branch_image(const std::string& technique, const std::string& scene_id, const RawParams& scene_params,
                            int size) {
  test::gl_context();
  const TechniqueDescriptor& descriptor = builtin_techniques().get(technique);
  const Scene scene = load_scene(scene_id, scene_params);
  const SceneGpu gpu(scene);
  std::unique_ptr<Technique> instance = descriptor.create(test::resolved_params(descriptor, {}, size, size));
  instance->resize(size, size);
  RenderTarget target(size, size);
  StageClock clock(ClockKind::wall);
  const Frame frame{gpu,  scene.camera.view,      scene.camera.projection(1.0f), size, size, glm::vec3(0.0f),
                    target.framebuffer.id(), clock};
  render_frame(*instance, frame, false);
  return read_texture_rgba32f(target.color.id(), size, size);
}

// The harness builds each run's programs for its scene's shading: unlit and
// lit scenes alternate in one process, and every image is bit for bit the
// run-time branch's.
TEST(SceneShading, ImagesAreTheRunTimeBranchsOnUnlitThenLitScenes) {
  const std::vector<std::pair<std::string, RawParams>> scenes = {
      {"quads", {{"layers", "6"}}}, {"spheres", {}}, {"quads", {{"layers", "5"}}}, {"torus", {}}};
  for (const char* technique : {"unsorted", "linked_list", "weighted_blended", "moment_oit", "depth_peeling"}) {
    for (const auto& [scene, scene_params] : scenes) {
      SCOPED_TRACE(std::string(technique) + " on " + scene);
      const RunResult run = test::render_once(technique, {}, scene, scene_params, 40, 40);
      const Image expected = run_time_branch_image(technique, scene, scene_params, 40);
      ASSERT_EQ(run.image.rgba.size(), expected.rgba.size());
      EXPECT_EQ(run.image.rgba, expected.rgba);
    }
  }
}

}  // namespace
}  // namespace oit
