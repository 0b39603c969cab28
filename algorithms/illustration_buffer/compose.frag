#version 450 core
// Compose (carnecky2013 section 4.6 / Algorithm 3): each pixel blends its
// contiguous sorted range front to back in float. Without modulation the
// opacity is the fragment's own alpha (plain alpha blending, the reference's
// operation order). With modulation (IB_MODULATE):
//   alpha_hat = (1 - gamma) * (alpha + (1 - alpha) * beta)
//   c += T * alpha_hat * c_i;  T *= 1 - alpha_hat
// after the optional profile (eq. 10 / 11) is applied to beta and gamma.
// IB_LOCAL_OPACITY (modulation=angle / normal_variation): the opacity the
// fill computed (fill.frag), read from the fragment's fill record, which
// these modes leave in place (no field ranges).
// IB_RAY_DISTANCE (modulation=ray_distance): pastyrik2016 eq. 1, the opacity
// of sample s_i from the view-depth distance to the next sample s_j behind it,
// saturate(|s_i.depth - s_j.depth| / focusRegion), in place of its own
// alpha; the farthest kept sample has none behind it: saturate(inf) = 1.
#include "shaders/compose.glsl"
#include "algorithms/illustration_buffer/ib_storage.glsl"
// The sorted ranges, colours and fields are read through the buffer-texture
// views (gathers on llvmpipe, where SSBO loads run lane by lane).
#include "algorithms/illustration_buffer/views.glsl"

layout(location = 0) out vec4 out_color;

#ifdef IB_MODULATE
#include "algorithms/illustration_buffer/fields.glsl"
#ifdef IB_SWEPT
// A frame whose diffusion swept: beta and gamma from the hop distances, and
// alpha the colour's (the sweeps run only where eq. 4 gives every fragment
// its own alpha and nothing moves it: stylize_init.comp).
#include "algorithms/illustration_buffer/sweep_distances.glsl"
#endif
// IB_PROFILE 0: none, 1: exponential (eq. 10), 2: power (eq. 11). A define,
// not a uniform: llvmpipe evaluates the exp and pow of a branch no lane takes.

float profile(float u) {
  u = clamp(u, 0.0, 1.0);
#if IB_PROFILE == 1
  const float floor_value = exp(-ib.profile_p);
  return (exp(-ib.profile_p * (1.0 - u) * (1.0 - u)) - floor_value) / (1.0 - floor_value);
#elif IB_PROFILE == 2
  return pow(u, ib.profile_p);
#else
  return u;
#endif
}
#endif

void main() {
  const uint pixel = uint(gl_FragCoord.y) * uint(ib.width) + uint(gl_FragCoord.x);
  const uint first = ib_pixel_first(pixel), end = first + ib_pixel_count(pixel);
  vec3 accumulated = vec3(0.0);
  float transmittance = 1.0;
#ifdef IB_RAY_DISTANCE
  float depth = end > first ? uintBitsToFloat(ib_sorted_key(first).x) : 0.0;  // s_i's view depth
#endif
  for (uint i = first; i < end; ++i) {
    const vec4 c = ib_sorted_color(i);
#if defined(IB_MODULATE)
#ifdef IB_SWEPT
    const vec4 field = vec4(c.a, ib_swept_fields(i), 0.0);
#else
    const vec4 field = texelFetch(ib_fields_view, int(i));
#endif
    const float alpha = clamp(field.x, 0.0, 1.0);
    const float opacity = (1.0 - profile(field.z)) * (alpha + (1.0 - alpha) * profile(field.y));
#elif defined(IB_LOCAL_OPACITY)
    const float opacity = uintBitsToFloat(ib_fragments[ib_sorted_geometry(i).w].surface.z);
#elif defined(IB_RAY_DISTANCE)
    float opacity = 1.0;
    if (i + 1u < end) {
      const float next = uintBitsToFloat(ib_sorted_key(i + 1u).x);
      opacity = clamp(abs(depth - next) / ib.focus_region, 0.0, 1.0);
      depth = next;
    }
#else
    const float opacity = c.a;
#endif
    const float weight = transmittance * opacity;
    accumulated += weight * c.rgb;
    transmittance *= 1.0 - opacity;
  }
  out_color = oit_finish(accumulated, transmittance);
}
