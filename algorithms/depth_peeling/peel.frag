#version 450 core
#include "shaders/subgroup_atomics.glsl"
// One depth-peeling pass (Everitt 2001). The previous pass left, per pixel,
// the key of the layer it peeled (see peel_shared.glsl). This pass discards
// every fragment peeled already; among the rest the hardware depth test
// (GL_LESS) keeps the next one, which writes its premultiplied colour and key.
//
// Peeling order is (view depth, submission index): the depth written is the
// view depth scaled exactly, and among equal depths GL_LESS keeps the first
// rasterised fragment, which (one draw call, fragments in primitive order)
// is the one with the lowest submission index. So fragments tied in depth
// are peeled one per pass, completely, in submission order.
//
// COUNT_SURVIVORS (1 only for the last pass max_passes allows): counts the
// fragments this pass sees un-peeled, so the host knows how many it leaves.
#include "shaders/shading.glsl"
#include "algorithms/depth_peeling/peel_shared.glsl"

layout(binding = DEPTH_PEELING_PREVIOUS_KEYS_UNIT) uniform usampler2D u_previous_keys;

layout(location = 0) out vec4 out_layer_color;  // premultiplied rgb, alpha
layout(location = 1) out uvec2 out_layer_key;

// 2^-64: maps positive view depths into the [0, 1] that gl_FragDepth is
// clamped to without rounding (a power of two only changes the exponent), so
// the depth test orders exactly by view depth for depths in [2^-62, 2^64)
// (the host checks the camera's depth range).
const float kDepthScale = 1.0 / 18446744073709551616.0;

void main() {
  const float depth = oit_view_depth();
  // The submission index, not the stable id oit_triangle_id(): only it
  // agrees with the order in which the depth test keeps equal depths.
  const uint submitted = uint(gl_PrimitiveID);
  const uvec2 previous = texelFetch(u_previous_keys, ivec2(gl_FragCoord.xy), 0).xy;
  if (!not_peeled_yet(depth, submitted, previous)) discard;
#if defined(COUNT_SURVIVORS) && COUNT_SURVIVORS
  OIT_ATOMIC_COUNT(survivors_of_last_pass);
#endif
  gl_FragDepth = depth * kDepthScale;
  const vec4 color = oit_shade();
  out_layer_color = vec4(color.rgb * color.a, color.a);
  out_layer_key = uvec2(floatBitsToUint(depth), submitted);
}
