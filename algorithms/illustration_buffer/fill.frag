#version 450 core
#if defined(IB_FETCH_CURSOR)
#extension GL_EXT_shader_framebuffer_fetch : require
#endif
#include "shaders/subgroup_atomics.glsl"
// Fill (carnecky2013 Algorithm 1, pastyrik2016 Algorithm 1): every fragment
// is appended to its pixel's list with its colour, depth, slopes, normal,
// object and triangle id. The list length is counted even when the pool is
// full, so the host learns how many records it needs (overflow -> grow and
// render again) and how long the longest list is.
// IB_RANGED (storage=linearized or arrays): a fragment takes the next record
// of its pixel's range from the pixel's cursor: an image atomic, or
// (IB_FETCH_CURSOR) the pixel's R32UI colour read and incremented in
// primitive order. No list, no global counter. linearized: the host already
// knows every count (the counting pass); pixel p owns records
// [offset[p], offset[p+1]) and its cursor starts at the offset. IB_ARRAYS
// (storage=arrays): pixel p owns the ib.slots records from p * ib.slots, its
// cursor starts at 0 and ends at its count (read back by the host); a
// fragment beyond the slots is not stored but still counted, and the host
// fills the frame again with more slots.
#include "shaders/shading.glsl"
#include "algorithms/illustration_buffer/ib_storage.glsl"


// The purely local opacities of carnecky2013 Fig. 11 (modulation=angle /
// normal_variation), stored in the record's slopes.z for the compose:
//  angle: the angle between the normal and the view ray, (2/pi) acos|n.v|
//    (0 facing the viewer, 1 at a silhouette; Hummel et al. 2010 [6]);
//  normal_variation: min(1, scale * |grad n|), grad n = (dn/dx, dn/dy) the
//    view normal's change per pixel (Born et al. [7]; carnecky2013: "the
//    derivatives of the surface normal").
layout(location = OIT_UNIFORM_PROJECTION) uniform mat4 u_projection;

// Unit vector from the fragment towards the eye along its view ray: +z for
// an orthographic camera (no perspective divide: projection[2][3] = 0).
vec3 to_eye() { return u_projection[2][3] == 0.0 ? vec3(0.0, 0.0, 1.0) : normalize(-v_view_position); }

#if defined(IB_FETCH_CURSOR)
layout(location = 0) inout uint ib_cursor;
#elif defined(IB_RANGED)
layout(binding = IB_CURSORS_IMAGE_UNIT, r32ui) uniform uimageBuffer ib_cursors;
#endif
#if defined(IB_ARRAYS)
#endif

#if defined(IB_RANGED)
// The pixel's cursor, advanced: this fragment's place in its pixel's range.
uint take_slot(uint pixel) {
#if defined(IB_FETCH_CURSOR)
  const uint slot = ib_cursor;
  ib_cursor = slot + 1u;
  return slot;
#else
  return imageAtomicAdd(ib_cursors, int(pixel), 1u);
#endif
}
#endif

// The record this fragment fills, or IB_NIL when the pool is full (storage=linked) or
// the pixel's slots are (arrays).
uint take_record(uint pixel) {
#if defined(IB_ARRAYS)
  const uint slot = take_slot(pixel);
  return slot < ib.slots ? pixel * ib.slots + slot : IB_NIL;
#elif defined(IB_RANGED)
  return take_slot(pixel);
#else
  const uint position = atomicAdd(ib_count[pixel], 1u);
  OIT_ATOMIC_RAISE(ib_longest, position + 1u);
  // Beyond the sort's array: counted here; the sort keeps the nearest max_per_pixel.
  if (position >= ib.max_per_pixel) {
    OIT_ATOMIC_COUNT(ib_dropped);
    if (position == ib.max_per_pixel) atomicAdd(ib_truncated, 1u);
  }
  uint index;
  OIT_ATOMIC_APPEND(ib_produced, index);
  return index < ib.capacity ? index : IB_NIL;  // pool overflow: the host grows the pool and re-renders
#endif
}


#ifdef IB_MEASURE
// Ground truth for the neighbour accuracy only (parameter measure_accuracy):
// x: surface id, yz: (u, v) bits, w: uv footprint of one pixel (fwidth, half2).
layout(std430, binding = IB_TRUTH_BINDING) buffer IbTruth { uvec4 ib_truth[]; };
#endif

void main() {
  // Derivatives first, in uniform control flow (before any early return).
  const float depth = oit_view_depth();
  const vec2 slopes = vec2(dFdx(depth), dFdy(depth));
  float local_opacity = 0.0;
#if defined(IB_ANGLE)
  local_opacity = acos(clamp(abs(dot(normalize(v_view_normal), to_eye())), 0.0, 1.0)) * (2.0 / 3.14159265358979);
#elif defined(IB_NORMAL_VARIATION)
  const vec3 normal = normalize(v_view_normal);
  const vec3 dndx = dFdx(normal), dndy = dFdy(normal);
  local_opacity = min(1.0, ib.normal_variation_scale * sqrt(dot(dndx, dndx) + dot(dndy, dndy)));
#endif
#ifdef IB_MEASURE
  const vec2 footprint = fwidth(v_uv);
#endif
  const uint pixel = uint(gl_FragCoord.y) * uint(ib.width) + uint(gl_FragCoord.x);
  const uint index = take_record(pixel);
  if (index == IB_NIL) return;
#if defined(IB_RANGED)
  // IB_FILL_RANGED (bindings.h): no link in contiguous ranges; key.w keeps
  // the light factor (1 unlit), from which the sort rebuilds the lit colour
  // of a flat colour record bit for bit (shading.glsl).
  const uint last_word = floatBitsToUint(oit_light_factor());
#else
  // IB_FILL_LINKED: key.w links the record to the pixel's old head.
  const uint last_word = atomicExchange(ib_head[pixel], index);
#endif
  const uvec4 key = uvec4(floatBitsToUint(depth), oit_triangle_id(), v_object_id, last_word);
#if defined(IB_SURFACE) && !defined(IB_FLAT_COLOR)
  const uvec4 surface = uvec4(floatBitsToUint(vec3(slopes, local_opacity)), ib_pack_normal(oit_view_normal()));
  ib_fragments[index] = IbFragment(oit_shade(), key, surface);
#else
  // IB_FLAT_COLOR (flat_color_records on an unlit scene, or a lit one with
  // contiguous ranges): the sort fetches the triangle's colour by its id
  // (times the light factor in key.w when ranged), so the fill stores no
  // colour (on llvmpipe each 16 B store at a per-lane address is a loop over
  // the lanes).
#ifndef IB_FLAT_COLOR
  ib_fragments[index].color = oit_shade();
#endif
  ib_fragments[index].key = key;
#ifdef IB_SURFACE
  ib_fragments[index].surface = uvec4(floatBitsToUint(vec3(slopes, local_opacity)), ib_pack_normal(oit_view_normal()));
#endif
#endif
#ifdef IB_MEASURE
  ib_truth[index] = uvec4(v_surface_id, floatBitsToUint(v_uv.x), floatBitsToUint(v_uv.y), packHalf2x16(footprint));
#endif
}
