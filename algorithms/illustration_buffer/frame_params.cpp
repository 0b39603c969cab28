#include "algorithms/illustration_buffer/frame_params.h"

#include <cstddef>
#include <vector>

#include "harness/toolkit/passes.h"
#include "harness/gl/check.h"

namespace oit::illustration_buffer {

// std140 lays 4-byte scalars out one after another, as C++ does here.
static_assert(sizeof(IbFrameParams) == 96 && offsetof(IbFrameParams, cutoff_gamma) == 4 * 20);
static_assert(sizeof(IbPassParams) == 16);

FrameParams::FrameParams(const Settings& s, uint32_t steps) : UniformBlock(IB_FRAME_PARAMS_BLOCK) {
  values.max_per_pixel = s.max_per_pixel;
  values.use_beta = s.uses_beta() ? 1u : 0u;
  values.use_gamma = s.uses_gamma() ? 1u : 0u;
  values.weight_z = s.weight_z;
  values.weight_n = s.weight_n;
  values.inverse_radius = 1.0f;
  values.lambda_alpha = s.lambda_alpha;
  values.lambda_beta = s.lambda_beta;
  values.lambda_gamma = s.lambda_gamma;
  values.tolerance = s.diffusion_tolerance;
  values.profile_p = s.profile == Profile::power ? s.power_p : s.exponential_p;
  values.normal_variation_scale = s.normal_variation_scale;
  values.focus_region = s.focus_region;
  GLint alignment = 1;
  glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &alignment);
  pass_stride_ = (GLsizeiptr(sizeof(IbPassParams)) + alignment - 1) / alignment * alignment;
  const size_t records = kSweeps + size_t(steps) + 1, per_record = size_t(pass_stride_) / sizeof(IbPassParams);
  std::vector<IbPassParams> passes(records * per_record, IbPassParams{});
  for (size_t r = 0; r < records; ++r) {
    IbPassParams& pass = passes[r * per_record];
    if (r < kSweeps) {
      pass.direction_x = kSweepDirections[r][0];
      pass.direction_y = kSweepDirections[r][1];
    } else {
      pass.next_step = uint32_t(r - kSweeps) + 1;  // step r - kSweeps queues for the step after
    }
  }
  passes_ = make_buffer(GLsizeiptr(passes.size() * sizeof(IbPassParams)), passes.data(), 0);
  gl_check("illustration_buffer: the parameter blocks");
}

void FrameParams::bind_pass(uint32_t index) const {
  glBindBufferRange(GL_UNIFORM_BUFFER, IB_PASS_PARAMS_BLOCK, passes_.id(), pass_stride_ * GLintptr(index),
                    sizeof(IbPassParams));
}

}  // namespace oit::illustration_buffer
