// illustration_buffer's binding points, units, record layouts, sentinels and
// its per-frame parameter block, included by its C++ and its GLSL alike so
// that no number or layout is copied by hand between the two
// (shaders/bindings.h: a technique's own start at OIT_FIRST_TECHNIQUE_*).
// What differs between the languages sits under __cplusplus: the C++ side
// names GLSL's scalar types, and the GLSL side declares the uniform blocks.
#ifndef OIT_ILLUSTRATION_BUFFER_BINDINGS_H
#define OIT_ILLUSTRATION_BUFFER_BINDINGS_H

#include "shaders/bindings.h"

// Sentinels the shaders write and the C++ clears with or reads back (accuracy.h).
#define IB_NIL 0xffffffffu        // end of a list
#define IB_NONE 0xffffffffu       // no geodesic neighbour in that direction
#define IB_OFF_IMAGE 0xfffffffeu  // the adjacent pixel lies outside the image

// Storage buffer binding points (ib_storage.glsl unless noted).
#define IB_HEAD_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 0)
#define IB_COUNT_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 1)
#define IB_NEXT_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 2)
#define IB_DATA_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 3)   // fragData: fill records, later both field ranges
#define IB_DATA2_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 4)  // fragData2: sorted search records
#define IB_COUNTERS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 5)
#define IB_TRUTH_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 6)       // fill.frag, measure_accuracy
#define IB_FIELDS_IN_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 7)   // fields.glsl
#define IB_FIELDS_OUT_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 8)  // fields.glsl
#define IB_DATA3_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 9)       // fragData3: sorted shade records and links
#define IB_STAMPS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 10)     // worklist.glsl (skip_converged)
#define IB_WORK_OUT_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 11)
#define IB_PIXEL_UPDATES_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 12)
#define IB_WORK_NEXT_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 13)  // stylize_diffuse.comp, IB_WORKLIST
#define IB_SEEDS_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 14)      // stylize_init.comp, IB_TRACK
#define IB_SWEEP_CHANGED_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 15)  // stylize_init.comp (IB_SWEEP_INIT), stylize_diffuse.comp (IB_CHECK)
#define IB_DISTANCES_BINDING (OIT_FIRST_TECHNIQUE_BINDING + 16)  // sweep_distances.glsl

// Uniform buffer binding points (ib_storage.glsl): the frame's parameters
// (IbFrameParams) and the parameters of one pass of a frame (IbPassParams).
#define IB_FRAME_PARAMS_BLOCK 0
#define IB_PASS_PARAMS_BLOCK 1

// Texture units of the read-only buffer-texture views. The per-fragment
// passes' (views.glsl) and the listed diffusion steps' (stylize_diffuse.comp):
#define IB_SEARCH_UNIT 0
#define IB_FIELDS_UNIT 1
#define IB_SHADE_UNIT 2
#define IB_WORK_UNIT 3
#define IB_HEAD_UNIT 4
#define IB_COUNT_UNIT 5
#define IB_SEEDS_UNIT 6  // stylize_seed_queue.comp
#define IB_LISTED_PIXELS_UNIT 7  // pixel_dispatch.glsl (IB_LISTED): sort.comp, neighbors_triangle_index.comp
#define IB_DISTANCES_UNIT 8      // sweep_distances.glsl: the sweeps' hop distances
#define IB_FIELD_TABLE_UNIT 9    // sweep_distances.glsl: beta and gamma by hop distance
// The sort's (sort.comp), a program of its own: fill records and the triangle table.
#define IB_FRAGMENT_UNIT 0
#define IB_SORT_TRIANGLES_UNIT 1  // neighbors=triangle_index
#define IB_OFFSETS_UNIT 2          // storage=linearized: the fill's per-pixel ranges; arrays: the fill's counts
// 3: free
#define IB_FLAT_COLORS_UNIT 4      // flat_color_records: the scene's colour per stable triangle id
// sort=static_arrays (sort_static_arrays.glsl): the entries of each of its
// three local arrays, pastyrik2016 section 4.1's 64 (the host checks max_per_pixel against it).
#define IB_STATIC_ENTRIES 64u
// Image units (fill.frag; the cursors with storage=linearized or arrays and fill=atomic).
#define IB_CURSORS_IMAGE_UNIT 0

// ---------------------------------------------------------------------------
// Record layouts. Each field below has one meaning in each named layout.
//
// The fill record (fragData, IbFragment: 3 texels of 16 B, IB_FILL_*_TEXEL):
//   color   straight RGBA from oit_shade() (not written with flat colour records)
//   key     x: view depth bits, y: stable triangle id, z: object id, w: by layout:
//             IB_FILL_LINKED (storage=linked): the next record of the pixel's list (IB_NIL: the end)
//             IB_FILL_RANGED (storage=linearized or arrays, each pixel's records
//               contiguous, so no link): the bits of the light factor
//               (shading.glsl; 1 unlit), from which the sort rebuilds the lit
//               colour of a flat colour record bit for bit
//   surface bits of x: d(depth)/dx, y: d(depth)/dy per pixel, z: the purely local
//           opacity (modulation=angle / normal_variation), w: the view normal
//           (octahedral snorm16x2); only where Settings::records_surface
#define IB_FILL_COLOR_TEXEL 0u
#define IB_FILL_KEY_TEXEL 1u
#define IB_FILL_SURFACE_TEXEL 2u
#define IB_FILL_TEXELS 3u
//
// The sorted search record (fragData2, IbSortedSearch, 2 texels):
//   key      x: view depth bits, y: stable triangle id, z: object id, w: pixel index
//   geometry w: the index of the fill record; xyz by layout:
//             IB_GEOMETRY_SURFACE (neighbors=heuristic*, and the purely local
//               modulations): x packed view normal, y dz/dx bits, z dz/dy bits
//             IB_GEOMETRY_TRIANGLE (neighbors=triangle_index): the vertex
//               indices of the fragment's triangle (sort.comp)
//             IB_GEOMETRY_NONE (modulation=none): 0
// The sorted shade record (fragData3, IbSortedShade, 2 texels):
//   color    straight RGBA
//   links    sorted indices of the left, right, down, up neighbours (or IB_NONE / IB_OFF_IMAGE)
//
// The fields (fields.glsl; two ranges of fragData after the sort), one vec4
// per sorted fragment: x alpha, y beta, z gamma, w the boundary flags.
#define IB_FIXED_BETA 1u   // the paper's b_beta = 0
#define IB_FIXED_GAMMA 2u  // b_gamma = 0
// The sweeps' hop distances (sweep_distances.glsl), one uint per sorted
// fragment: beta's in bits 0-15, gamma's in 16-31; each half the bit
// IB_DISTANCE_FIXED for a boundary condition and the distance,
// IB_DISTANCE_FAR where no seed has reached it.
#define IB_DISTANCE_FIXED 0x8000u
#define IB_DISTANCE_FAR 0x7fffu

// ---------------------------------------------------------------------------
// Parameters of a frame, one std140 uniform block (IB_FRAME_PARAMS_BLOCK).
// Every member is a 4-byte scalar, so std140 packs them as C++ does
// (static_assert in frame_params.cpp); booleans are uints.
#ifdef __cplusplus
#include <cstdint>
namespace oit::illustration_buffer {
using uint = std::uint32_t;
#endif
struct IbFrameParams {
  int width, height;           // the frame's pixels
  uint capacity;               // storage=linked: records in the pool (fill.frag)
  uint max_per_pixel;          // the sort's longest kept list (fill.frag, sort.comp IB_DYNAMIC)
  uint slots;                  // storage=arrays: records per pixel (fill.frag, sort.comp)
  uint fragments;              // the stored fragments (per_fragment.glsl)
  uint listed_pixels;          // the covered pixels (pixel_dispatch.glsl, IB_LISTED)
  uint use_beta, use_gamma;    // the modulation's fields (stylize_init.comp)
  float weight_z, weight_n;    // eq. 3 (neighbors.comp)
  float inverse_radius;        // 1 / r_obj of eq. 1 (neighbors.comp)
  float lambda_alpha, lambda_beta, lambda_gamma;  // eq. 8-9 (stylize_diffuse.comp)
  float tolerance;             // diffusion_tolerance (stylize_diffuse.comp, IB_WORKLIST)
  float profile_p;             // eq. 10 / 11 (compose.frag)
  float normal_variation_scale;  // fill.frag, IB_NORMAL_VARIATION
  uint table_size;             // entries per field of the sweeps' table (sweep_distances.glsl)
  uint cutoff_beta, cutoff_gamma;  // each field's first distance of value 0 (stylize_diffuse.comp)
  float focus_region;          // eq. 1 of pastyrik2016 (compose.frag, IB_RAY_DISTANCE)
  uint unused_0, unused_1;     // the block padded to a multiple of 16 bytes
};
// Parameters of one pass of a frame (IB_PASS_PARAMS_BLOCK, bound per pass
// at its record: frame_params.h).
struct IbPassParams {
  int direction_x, direction_y;  // a sweep's direction (stylize_diffuse.comp, IB_SWEEP)
  uint next_step;                // the step a listed step queues pixels for (worklist.glsl)
  uint unused;
};
#ifdef __cplusplus
}  // namespace oit::illustration_buffer
#endif

#endif
