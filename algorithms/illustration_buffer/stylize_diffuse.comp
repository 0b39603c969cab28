#version 450 core
// One diffusion iteration (carnecky2013 section 5.4), reading one field
// range and writing the other:
//  alpha <- alpha + lambda_alpha * laplacian(alpha)               (eq. 8)
//     with the Laplacian normalised by the neighbour count,
//     mean(alpha_neighbours - alpha), so that lambda_alpha in [0, 1] is a
//     convex blend (stable; lambda_alpha = 1 is the paper's default);
//     missing neighbours are left out (zero flux across silhouettes).
//     The mean of the differences, not of the values, so that equal
//     neighbours give exactly alpha (stylize_init relies on it);
//  u <- max(u, max(u_neighbours) - lambda_u), u in {beta, gamma}  (eq. 9)
//     unless the fragment's u is fixed by a boundary condition (b_u = 0);
//  or, IB_HOMOGENEOUS_FIELDS (field_diffusion=homogeneous), eq. 8 for them
//     as for alpha: u <- u + lambda_u * mean(u_neighbours - u) unless fixed.
// Variants of diffusion=steps: plain (skip_converged=false), one invocation
// per sorted fragment; IB_WORKLIST (every step with skip_converged): one
// invocation per queued pixel, which updates the pixel's fragments, and a
// fragment that moved by more than ib.tolerance queues the pixels around it
// for the next step (worklist.glsl). The first step's pixels are queued by
// stylize_init. Of diffusion=sweep: IB_SWEEP, in place along the rows, and
// IB_CHECK, whether any fragment would still move (below), both on hop
// distances (sweep_distances.glsl).
// With skip_converged a move of at most ib.tolerance is not applied (the
// fragment keeps its value), so a fragment that is not queued has its value
// in both field ranges.
#include "algorithms/illustration_buffer/ib_storage.glsl"
#include "algorithms/illustration_buffer/per_fragment.glsl"
#include "algorithms/illustration_buffer/fields.glsl"
#include "algorithms/illustration_buffer/views.glsl"


#ifdef IB_HOMOGENEOUS_FIELDS
// Eq. 8: beta and gamma of a fragment with fields `field` whose linked
// neighbours' beta and gamma differ from its own by `difference` in sum
// over `neighbors` of them (> 0): the normalised Laplacian, as alpha's.
vec2 smoothed(vec4 field, vec2 difference, float neighbors) {
  const uint flags = ib_flags(field);
  const vec2 moved = field.yz + vec2(ib.lambda_beta, ib.lambda_gamma) * (difference / neighbors);
  return vec2((flags & IB_FIXED_BETA) != 0u ? field.y : moved.x, (flags & IB_FIXED_GAMMA) != 0u ? field.z : moved.y);
}
#else
// Eq. 9: beta and gamma of a fragment with fields `field` whose linked
// neighbours' largest beta and gamma are `most`.
vec2 raised(vec4 field, vec2 most) {
  const uint flags = ib_flags(field);
  return vec2((flags & IB_FIXED_BETA) != 0u ? field.y : max(field.y, most.x - ib.lambda_beta),
              (flags & IB_FIXED_GAMMA) != 0u ? field.z : max(field.z, most.y - ib.lambda_gamma));
}
#endif

// The fields of fragment s after one iteration.
vec4 diffused(uint s, vec4 field) {
  const uvec4 links = ib_sorted_links(s);
  float alpha_difference = 0.0, neighbors = 0.0;
#ifdef IB_HOMOGENEOUS_FIELDS
  vec2 field_difference = vec2(0.0);
#else
  vec2 most = vec2(0.0);
#endif
  for (int d = 0; d < 4; ++d) {
    if (links[d] >= IB_OFF_IMAGE) continue;
    const vec4 other = texelFetch(ib_fields_view, int(links[d]));
    alpha_difference += other.x - field.x;
    neighbors += 1.0;
#ifdef IB_HOMOGENEOUS_FIELDS
    field_difference += other.yz - field.yz;
#else
    most = max(most, other.yz);
#endif
  }
  const float alpha = neighbors > 0.0 ? field.x + ib.lambda_alpha * (alpha_difference / neighbors) : field.x;
#ifdef IB_HOMOGENEOUS_FIELDS
  return vec4(alpha, neighbors > 0.0 ? smoothed(field, field_difference, neighbors) : field.yz, field.w);
#else
  return vec4(alpha, raised(field, most), field.w);
#endif
}

#if defined(IB_WORKLIST)
#include "algorithms/illustration_buffer/worklist.glsl"

// Updates fragment s; true when it moved by more than the tolerance.
bool update(uint s) {
  const vec4 field = texelFetch(ib_fields_view, int(s));
  const vec4 next = diffused(s, field);
  const vec3 moved = abs(next.xyz - field.xyz);
  const bool changed = max(moved.x, max(moved.y, moved.z)) > ib.tolerance;
  ib_fields_out[s] = changed ? next : field;
  return changed;
}

// The step's list (header: groups x, y, z, count; then pixels), read as a
// buffer texture (a gather on llvmpipe, views.glsl).
layout(binding = IB_WORK_UNIT) uniform usamplerBuffer ib_work_view;

// The list of the step after next (read by the step before): emptied here,
// so that no host upload sits between the dispatches.
layout(std430, binding = IB_WORK_NEXT_BINDING) writeonly buffer IbWorkNext { uvec4 ib_next_header; };

void main() {
  if (gl_GlobalInvocationID.x == 0u) ib_next_header = uvec4(1u, 1u, 1u, 0u);
  const uint stride = gl_NumWorkGroups.x * 64u, count = texelFetch(ib_work_view, 3).x;
  for (uint e = gl_GlobalInvocationID.x; e < count; e += stride) {
    const uint pixel = texelFetch(ib_work_view, int(4u + e)).x;
    const uint first = ib_pixel_first(pixel), end = first + ib_pixel_count(pixel);
    bool changed = false;
    for (uint s = first; s < end; ++s) changed = update(s) || changed;
    ib_pixel_updates[pixel] += end - first;
    if (changed) ib_enqueue_around(pixel);
  }
}
#elif defined(IB_SWEEP) || defined(IB_CHECK)
// diffusion=sweep runs only where alpha cannot move (every fragment starts
// with the scene's one alpha, eq. 4, and eq. 8 of equal values is exactly
// alpha): so only beta and gamma move, carried as hop distances
// (sweep_distances.glsl), which spares llvmpipe the gathers of whole field
// texels.
#include "algorithms/illustration_buffer/sweep_distances.glsl"

// Beta's and gamma's first distance whose value is 0 (F(d) <= 0): no
// farther distance is kept (it stays IB_DISTANCE_FAR), as eq. 9 carries
// nothing from a value of 0, so the sweeps stop where the values do.

// Eq. 9 in distances: fragment s's distances `own` after one step, each
// unfixed one the nearest linked neighbour's + 1 where that is nearer and
// below the cutoff.
uint swept(uint s, uint own) {
  const uvec4 links = ib_sorted_links(s);
  uvec2 nearest = uvec2(IB_DISTANCE_FAR);
  for (int d = 0; d < 4; ++d)
    if (links[d] < IB_OFF_IMAGE)
      nearest = min(nearest, ib_unpack_distances(texelFetch(ib_distances_view, int(links[d])).x) & IB_DISTANCE_FAR);
  const uvec2 mine = ib_unpack_distances(own);
  const uvec2 offered = mix(uvec2(IB_DISTANCE_FAR), nearest + 1u, lessThan(nearest + 1u, uvec2(ib.cutoff_beta, ib.cutoff_gamma)));
  return ib_pack_distances(mix(min(mine, offered), mine, notEqual(mine & IB_DISTANCE_FIXED, uvec2(0u))));
}

#if defined(IB_SWEEP)
// In place, one invocation per image row, the rows in the order of
// ib_pass.direction_y and each walked in the order of ib_pass.direction_x. Lane k of a
// SIMD group starts k pixels late, so that the row before its own (lane
// k - 1, or the group before) has updated a pixel when it reads it: a pass
// carries values along any path that goes only in its two directions (a
// raster-order chamfer pass). Values read from other workgroups may be
// old; that only slows the convergence (distances only fall).

void main() {
  const uint width = uint(ib.width), height = uint(ib.height), index = gl_GlobalInvocationID.x;
  if (index >= height) return;
  const uint y = ib_pass.direction_y > 0 ? index : height - 1u - index, lag = index % 8u;
  for (uint t = 0u; t < width + 7u; ++t) {
    if (t < lag || t - lag >= width) continue;
    const uint x = ib_pass.direction_x > 0 ? t - lag : width - 1u - (t - lag);
    const uint pixel = y * width + x, first = ib_pixel_first(pixel), end = first + ib_pixel_count(pixel);
    for (uint s = first; s < end; ++s) {
      const uint own = texelFetch(ib_distances_view, int(s)).x, next = swept(s, own);
      if (next != own) ib_distances[s] = next;
    }
  }
}
#else
// The convergence check: one invocation per fragment; 1 when a step would
// move a distance (the sweeps have not reached the fixed point yet).
layout(std430, binding = IB_SWEEP_CHANGED_BINDING) writeonly buffer IbSweepChanged { uint ib_sweep_changed; };

void main() {
  const uint s = ib_fragment_index();
  if (s >= ib.fragments) return;
  const uint own = texelFetch(ib_distances_view, int(s)).x;
  if (swept(s, own) != own) ib_sweep_changed = 1u;
}
#endif
#else
void main() {
  const uint s = ib_fragment_index();
  if (s >= ib.fragments) return;
  ib_fields_out[s] = diffused(s, texelFetch(ib_fields_view, int(s)));
}
#endif
