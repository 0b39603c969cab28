#include "harness/toolkit/technique.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "base/suggest.h"
#include "harness/toolkit/stage_clock.h"
#include "harness/gl/uniforms.h"

#include "shaders/bindings.h"

namespace oit {

// Shared uniforms are optional in a program (a depth-only pass has no u_lit,
// a compose pass no matrices).
void Frame::set_shared_uniforms(GLuint program) const {
  // The one place every pass goes through: a program built for the other
  // shading would draw this scene wrongly (gl/shader_program.h).
  const SceneShading built_for = scene_shading_of(program);
  if (built_for != SceneShading::any && built_for != scene.shading())
    throw std::logic_error("program " + std::to_string(program) + " was built for " + to_string(built_for) +
                           " scenes but draws " + to_string(scene.shading()) + " scene '" + scene.scene().name +
                           "': create the technique under a SceneShadingScope of the scene it renders");
  if (uniform_active(program, "u_view")) set_uniform(program, OIT_UNIFORM_VIEW, view);
  if (uniform_active(program, "u_projection")) set_uniform(program, OIT_UNIFORM_PROJECTION, projection);
  if (uniform_active(program, "u_lit")) set_uniform(program, OIT_UNIFORM_LIT, scene.scene().lit ? 1 : 0);
  if (uniform_active(program, "u_pixel_origin"))
    set_uniform(program, OIT_UNIFORM_PIXEL_ORIGIN, glm::ivec2(origin_x, origin_y));
  if (uniform_active(program, "u_background")) set_uniform(program, OIT_UNIFORM_BACKGROUND, background);
}

void Frame::bind_target() const {
  glBindFramebuffer(GL_FRAMEBUFFER, target_framebuffer);
  glViewport(0, 0, width, height);
}

glm::vec2 Frame::near_far() const {
  // glm: m[column][row]; perspective when m[2][3] == -1, else orthographic.
  const glm::mat4& p = projection;
  if (p[2][3] != 0.0f) return {p[3][2] / (p[2][2] - 1.0f), p[3][2] / (p[2][2] + 1.0f)};
  return {(p[3][2] + 1.0f) / p[2][2], (p[3][2] - 1.0f) / p[2][2]};
}

const char* to_string(Exactness exactness) {
  switch (exactness) {
    case Exactness::exact: return "exact";
    case Exactness::exact_while_storage_covers: return "exact while storage covers";
    case Exactness::approximate: return "approximate";
  }
  return "approximate";
}

bool held_to_reference(Exactness exactness, uint64_t fragments_dropped) {
  return exactness != Exactness::approximate && fragments_dropped == 0;
}

std::optional<double> find_figure(const std::vector<Figure>& figures, const std::string& name) {
  for (const Figure& figure : figures)
    if (figure.name == name) return figure.value;
  return std::nullopt;
}

std::string supports(const TechniqueDescriptor& technique, const ParamSet& params, const DeviceProfile& device,
                     const SceneFacts& scene) {
  if (technique.needs.fp64 && !device.fp64) return "device has no double-precision shaders (GL_ARB_gpu_shader_fp64)";
  if (technique.needs.int64 && !device.int64) return "device has no 64-bit integers in shaders (GL_ARB_gpu_shader_int64)";
  if (technique.needs.indexed_geometry && !scene.indexed) return "scene has no shared vertex indices";
  if (technique.needs.multiple_objects && scene.objects < 2) return "scene has a single object";
  return technique.extra_support_check ? technique.extra_support_check(params, scene, device) : "";
}

ParamSet resolve_params(const TechniqueDescriptor& technique, const ResolveInput& input) {
  const std::string owner = "technique '" + technique.id + "' (as resolved for " + input.device.renderer + ")";
  RawParams asked = input.given;
  const ParamSet requested(technique.params, input.given, owner);
  if (!technique.paper_preset.empty() && requested.choice(kPresetParameter) == "paper")
    for (const auto& [key, value] : technique.paper_preset) asked.emplace(key, value);
  if (!technique.resolve) return ParamSet(technique.params, asked, owner);
  RawParams resolved = asked;
  const ParamSet preset(technique.params, asked, owner);
  for (const auto& [key, value] : technique.resolve(preset, {input.device, input.scene, input.content, asked}))
    resolved[key] = value;
  return ParamSet(technique.params, resolved, owner);
}

void TechniqueRegistry::add(TechniqueDescriptor descriptor) {
  for (const auto& existing : techniques_) {
    if (existing.id == descriptor.id) throw std::logic_error("technique '" + descriptor.id + "' registered twice");
  }
  if (!descriptor.create) throw std::logic_error("technique '" + descriptor.id + "' has no factory");
  for (size_t i = 0; i < descriptor.stages.size(); ++i) {
    const std::string& stage = descriptor.stages[i];
    if (!is_stage_name(stage) || stage == "total" ||
        std::find(descriptor.stages.begin(), descriptor.stages.begin() + long(i), stage) != descriptor.stages.begin() + long(i))
      throw std::logic_error("technique '" + descriptor.id + "' declares stage '" + stage +
                             "': stages are distinct snake_case names other than 'total' (the harness's)");
  }
  if (!descriptor.paper_preset.empty()) {
    std::string values;
    for (const auto& [key, value] : descriptor.paper_preset) {
      if (std::none_of(descriptor.params.begin(), descriptor.params.end(),
                       [&](const ParamSpec& spec) { return spec.name == key; }))
        throw std::logic_error("technique '" + descriptor.id + "': its paper preset sets '" + key +
                               "', which it has no parameter of");
      values += (values.empty() ? "" : " ") + key + "=" + value;
    }
    descriptor.params.push_back(ParamSpec::choice(
        std::string(kPresetParameter), "none", {"none", "paper"},
        "paper = the published algorithm: " + values + " (where not set); none = the defaults"));
  }
  techniques_.push_back(std::move(descriptor));
}

std::vector<std::string> TechniqueRegistry::ids() const {
  std::vector<std::string> ids;
  for (const auto& technique : techniques_) ids.push_back(technique.id);
  return ids;
}

const TechniqueDescriptor& TechniqueRegistry::get(const std::string& id) const {
  for (const auto& technique : techniques_) {
    if (technique.id == id) return technique;
  }
  const std::vector<std::string> known = ids();
  std::string list;
  for (const auto& name : known) list += (list.empty() ? "" : ", ") + name;
  throw std::invalid_argument("unknown technique '" + id + "'" + did_you_mean(id, known) + " (registered: " + list + ")");
}

const TechniqueDescriptor& TechniqueRegistry::reference() const {
  for (const auto& technique : techniques_)
    if (technique.is_reference) return technique;
  throw std::logic_error("no reference technique is registered");
}

}  // namespace oit
