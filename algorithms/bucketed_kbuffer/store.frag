#version 450 core
// Data pass (murray2016 4.1 "Data storage", Figure 4): the second geometry
// pass. Each fragment finds its bucket by its shape id (BUCKETS =
// BKB_BUCKETS_SINGLE: the whole list), then its slot by a
// binary search on the key inside the bucket, and stores its colour (RGBA8)
// and normal there. Fragments beyond the K nearest find no slot. Fragments
// with identical keys (same shape, same quantised depth) each claim their
// own slot with an atomic compare-and-swap on the cleared normal word.
#include "shaders/shading.glsl"
#include "algorithms/bucketed_kbuffer/bkb_common.glsl"

layout(location = OIT_UNIFORM_PROJECTION) uniform mat4 u_projection;

// Unit vector from the fragment towards the viewer (orthographic: +z).
vec3 to_viewer() { return u_projection[2][3] == 0.0 ? vec3(0.0, 0.0, 1.0) : -v_view_position; }

void main() {
#if MEASURE_ACCURACY
  // Before any invocation of the quad returns: derivatives need all four.
  vec2 footprint = fwidth(v_uv);
#endif
  uint shape = v_object_id & BKB_SHAPE_MASK;
  uint key = bkb_shape_key(shape, bkb_quantise_depth(oit_view_depth()));
  uint base = bkb_pixel_base();
  uvec2 bucket;
#if BUCKETS == BKB_BUCKETS_SINGLE
  // One object: every kept fragment shares this shape, the list is the bucket.
  bucket = bkb_whole_list(base);
  if (bucket.x > bucket.y) return;
#else
  if (!bkb_find_bucket(base, shape, bucket)) return;
#endif
  uint low = bucket.x, high = bucket.y + 1u;  // lower bound of key in [first, last]
  while (low < high) {
    uint middle = (low + high) >> 1;
    if (bkb_z[base + middle] < key) low = middle + 1u; else high = middle;
  }
  // The normal facing the viewer, whatever the triangle winding, so that
  // curvature signs mean the same on every mesh.
  vec3 raw = v_view_normal;
  bool outward_faces_viewer = dot(raw, to_viewer()) >= 0.0;
  vec3 normal = dot(raw, raw) > 0.0 ? normalize(outward_faces_viewer ? raw : -raw) : vec3(0.0, 0.0, 1.0);
  uint normal_word = bkb_pack_normal(normal);
  for (uint slot = low; slot <= bucket.y; ++slot) {
    if (bkb_z[base + slot] != key) return;
    if (atomicCompSwap(bkb_normals[base + slot], 0u, normal_word) != 0u) continue;  // taken by an equal key
    bkb_colors[base + slot] = packUnorm4x8(oit_shade());
#if MEASURE_ACCURACY
    // Analytic k1 + k2 in the viewer-facing convention of neighbors.frag:
    // the scene's mean curvature H belongs to its own (outward) normal;
    // a surface bulging towards the viewer is negative.
    bkb_expected[base + slot] = -2.0 * v_mean_curvature * (outward_faces_viewer ? 1.0 : -1.0);
    bkb_truth[base + slot] = uvec4(v_surface_id, floatBitsToUint(v_uv.x), floatBitsToUint(v_uv.y),
                                   packHalf2x16(footprint));
#endif
    return;
  }
}
