#version 450 core
// Accumulation pass (Enderton et al., section 3.2): every fragment again,
// into a multisampled target sharing the stochastic depth buffer, with the
// depth test LEQUAL and no depth writes. The fragment's (a rgb, a) is added
// at each of its samples where no nearer fragment covered the sample, so
// the average over the pixel's samples (compose) weights it by the share of
// unoccluded samples: an unbiased estimate of prod over nearer fragments of
// (1 - alpha). Rasterised exactly like the depth pass, every sample's depth
// matches what that pass stored.
#include "shaders/shading.glsl"

layout(location = 0) out vec4 out_accumulation;

void main() {
  const vec4 color = oit_shade();
  out_accumulation = color.a * vec4(color.rgb, 1.0);
}
