#pragma once
// Every compile-time switch of the illustration buffer's shaders, in one
// struct: each stage fills the members its programs read and builds them
// from defines(), the one place a define is spelled. A member left at its
// default emits nothing.
#include <cstdint>

#include "harness/gl/shader_program.h"

namespace oit::illustration_buffer {

struct ShaderVariant {
  // Storage (fill.frag, sort.comp): IB_RANGED, each pixel's records
  // contiguous (storage=linearized or arrays); IB_ARRAYS, in per-pixel
  // arrays of ib.slots records; IB_FETCH_CURSOR, the slot taken by
  // framebuffer fetch; IB_LISTED, the per-pixel passes dispatched over the
  // covered pixels (pixel_dispatch.glsl).
  bool ranged = false, arrays = false, fetch_cursor = false, listed = false;
  // The fill record (bindings.h): IB_FLAT_COLOR, no colour (the sort fetches
  // the triangle's); IB_MEASURE, the ground truth; IB_SURFACE, the slopes,
  // normal and local opacity; IB_ANGLE / IB_NORMAL_VARIATION, the purely
  // local opacity the fill computes.
  bool flat_color = false, measure = false, surface = false, angle = false, normal_variation = false;
  // The sort (sort.comp): IB_ARRAY, its local array's size (0: none);
  // IB_DYNAMIC, pastyrik2016's insertion sort; IB_STATIC_ARRAYS, its
  // selection sort in static arrays; IB_TRUNCATES, the path for lists longer
  // than the array; IB_TRIANGLE_VERTICES, the geometry layout
  // IB_GEOMETRY_TRIANGLE.
  uint32_t sort_array = 0;
  bool dynamic_sort = false, static_arrays = false, truncates = false, triangle_vertices = false;
  // The neighbour searches: IB_MERGE (neighbors.comp, heuristic_merge);
  // IB_GROUP, fragments per group (neighbors_triangle_index.comp; 0: none).
  bool merge = false;
  uint32_t group = 0;
  // Stylize (stylize_init.comp): IB_TRACK, the first step's seeds
  // (skip_converged); IB_ALPHA_SEEDS, also where alpha differs;
  // IB_SWEEP_INIT, the sweeps' distances; IB_ADAPTIVE, eq. 5.
  bool track = false, alpha_seeds = false, sweep_init = false, adaptive = false;
  // The diffusion (stylize_diffuse.comp): every fragment (plain), the listed
  // pixels (IB_WORKLIST), a sweep (IB_SWEEP) or the sweeps' check (IB_CHECK);
  // IB_HOMOGENEOUS_FIELDS, beta and gamma by eq. 8 instead of eq. 9.
  enum class Diffuse { plain, worklist, sweep, check };
  Diffuse diffuse = Diffuse::plain;
  bool homogeneous_fields = false;
  // The compose (compose.frag): IB_MODULATE with IB_PROFILE (Profile's
  // value), IB_SWEPT (fields from the sweeps' distances), IB_LOCAL_OPACITY,
  // IB_RAY_DISTANCE (pastyrik2016 eq. 1).
  bool modulate = false, swept = false, local_opacity = false, ray_distance = false;
  int profile = 0;

  ShaderDefines defines() const;
};

}  // namespace oit::illustration_buffer
