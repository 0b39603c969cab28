#version 450 core
// One diffusion iteration (carnecky2013 section 5.4), one invocation per
// sorted fragment, reading one field range and writing the other:
//  alpha <- alpha + lambda_alpha * laplacian(alpha)               (eq. 8)
//     with the Laplacian normalised by the neighbour count,
//     mean(alpha_neighbours) - alpha, so that lambda_alpha in [0, 1] is a
//     convex blend (stable; lambda_alpha = 1 is the paper's default);
//     missing neighbours are left out (zero flux across silhouettes);
//  u <- max(u, max(u_neighbours) - lambda_u), u in {beta, gamma}  (eq. 9)
//     unless the fragment's u is fixed by a boundary condition.
#include "algorithms/illustration_buffer/ib_storage.glsl"
#include "algorithms/illustration_buffer/per_fragment.glsl"
#include "algorithms/illustration_buffer/fields.glsl"
#include "algorithms/illustration_buffer/views.glsl"

layout(location = IB_LAMBDA_ALPHA_LOCATION) uniform float u_lambda_alpha;
layout(location = IB_LAMBDA_BETA_LOCATION) uniform float u_lambda_beta;
layout(location = IB_LAMBDA_GAMMA_LOCATION) uniform float u_lambda_gamma;

float alpha_sum = 0.0, neighbors = 0.0, beta_max = 0.0, gamma_max = 0.0;

void gather(uint link) {
  if (link >= IB_OFF_IMAGE) return;
  const vec4 field = texelFetch(ib_fields_view, int(link));
  alpha_sum += field.x;
  neighbors += 1.0;
  beta_max = max(beta_max, field.y);
  gamma_max = max(gamma_max, field.z);
}

void main() {
  const uint s = ib_fragment_index();
  if (s >= u_fragments) return;
  const vec4 field = texelFetch(ib_fields_view, int(s));
  const uvec4 links = ib_sorted_links(s);
  gather(links.x);
  gather(links.y);
  gather(links.z);
  gather(links.w);
  const uint flags = ib_flags(field);
  const float alpha = neighbors > 0.0 ? field.x + u_lambda_alpha * (alpha_sum / neighbors - field.x) : field.x;
  const float beta = (flags & IB_FIXED_BETA) != 0u ? field.y : max(field.y, beta_max - u_lambda_beta);
  const float gamma = (flags & IB_FIXED_GAMMA) != 0u ? field.z : max(field.z, gamma_max - u_lambda_gamma);
  ib_fields_out[s] = vec4(alpha, beta, gamma, field.w);
}
