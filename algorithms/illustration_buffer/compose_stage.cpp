#include "algorithms/illustration_buffer/compose_stage.h"

#include "algorithms/illustration_buffer/bindings.h"
#include "algorithms/illustration_buffer/shader_variant.h"
#include "harness/gl/shader_program.h"

namespace oit::illustration_buffer {

ComposeStage::ComposeStage(const Settings& s) {
  ShaderVariant v;
  v.modulate = s.diffused();
  v.profile = int(s.profile);
  v.local_opacity = !s.diffused() && s.purely_local();
  v.ray_distance = s.modulation == Modulation::ray_distance;
  compose_ = build_fullscreen_program("algorithms/illustration_buffer/compose.frag", v.defines());
  if (s.diffused() && s.may_sweep()) {  // the swept frames' compose reads the hop distances (sweep_distances.glsl)
    v.swept = true;
    swept_ = build_fullscreen_program("algorithms/illustration_buffer/compose.frag", v.defines());
  }
}

void ComposeStage::run(const Frame& frame, const FramePlan& plan) const {
  auto stage = frame.clock.stage("compose");
  frame.bind_target();
  const GLuint compose = plan.swept ? swept_.id() : compose_.id();
  glUseProgram(compose);
  frame.set_shared_uniforms(compose);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  for (GLuint unit : {IB_SEARCH_UNIT, IB_FIELDS_UNIT, IB_SHADE_UNIT, IB_WORK_UNIT, IB_HEAD_UNIT, IB_COUNT_UNIT,
                      IB_FRAGMENT_UNIT, IB_SORT_TRIANGLES_UNIT, IB_OFFSETS_UNIT, IB_FLAT_COLORS_UNIT, IB_SEEDS_UNIT,
                      IB_LISTED_PIXELS_UNIT, IB_DISTANCES_UNIT, IB_FIELD_TABLE_UNIT})
    glBindTextureUnit(unit, 0);
}

}  // namespace oit::illustration_buffer
