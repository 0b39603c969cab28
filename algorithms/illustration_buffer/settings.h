#pragma once
// The validated parameters of the illustration buffer, typed.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "harness/toolkit/list_length_pass.h"
#include "harness/toolkit/technique.h"

namespace oit::illustration_buffer {

// heuristic_merge: the heuristic's candidate found by a walk of the
// depth-sorted list (the same links, fewer candidates scored).
enum class NeighborSearch { heuristic, heuristic_merge, triangle_index };
// Which of carnecky2013's fields modulate the opacity: none (plain alpha
// blending; no neighbour search, no stylize), beta (silhouette), gamma
// (halo) or both; or one of the purely local baselines of its Fig. 11
// (opacity from the angle between normal and view ray, or from the
// normal's screen-space variation; no neighbour search, no stylize); or
// pastyrik2016's eq. 1, the opacity from the distance along the ray to the
// next sample (ray_distance; in the compose, no neighbour search, no stylize).
enum class Modulation { none, silhouette, halo, silhouette_halo, angle, normal_variation, ray_distance };
// The sort: ranks in a local array (carnecky2013 section 4.3), or
// pastyrik2016's Algorithm 2, insertion sort of the linked list in place, or
// per frame the faster of the two on llvmpipe for the frame's longest list;
// or pastyrik2016's selection sort in three static arrays of 64 entries
// (its section 3.2 and Fig. 7), never chosen by auto.
enum class SortMethod { automatic, array, dynamic, static_arrays };
enum class Profile { none, exponential, power };  // eq. 10 / eq. 11
// How beta and gamma spread from their boundary values (carnecky2013
// section 5.4): the paper's nonphysical process, u <- max(u, max(u_n) -
// lambda_u) (eq. 9), or the homogeneous diffusion it uses for alpha,
// u <- u + b_u lambda_u laplacian(u) (eq. 8; normalised Laplacian).
enum class FieldDiffusion { nonphysical, homogeneous };
// Where the fill puts the records: per-pixel linked lists in a pool sized
// from the previous frame (carnecky2013 Algorithm 1), or a linearized
// buffer (Knowles et al. 2012): a counting pass and each pixel's range
// from the counts' prefix sum, exactly sized, filled in place; or
// fixed-size per-pixel arrays of as many slots as the previous frame's
// longest list (no counting pass; a longer list is caught by its cursor and
// the fill runs again with more slots); or, a software rasterizer's choice,
// linearized with per-pixel arrays on the frames after one whose lists were
// even (arrays_when_even: one geometry pass fewer where each pass is costly).
// automatic is resolved by the registry's resolution rule and never reaches
// the technique.
enum class Storage { automatic, linked, linearized, arrays, arrays_when_even };
// How the diffusion reaches its result: `iterations` synchronous steps of
// eq. 8-9, or in-place sweeps along the image lines until nothing moves (the
// fixed point, which equals the steps' result when alpha cannot move and
// `iterations` steps carry beta and gamma to 0: sweep_reaches_steps), or,
// a software rasterizer's choice, sweeps on the frames where they are exact
// and steps elsewhere (sweep_where_exact). auto is resolved by the
// registry's resolution rule: sweep_where_exact on a software rasterizer,
// steps on a GPU.
enum class Diffusion { automatic, steps, sweep, sweep_where_exact };

struct Settings {
  NeighborSearch neighbors = NeighborSearch::triangle_index;
  Modulation modulation = Modulation::silhouette_halo;
  bool adaptive_alpha = false;  // eq. 5 instead of eq. 4
  int iterations = 20;
  bool skip_converged = true;       // diffuse only the pixels whose neighbourhood changed
  float diffusion_tolerance = 0.0f; // a fragment moving by at most this keeps its value
  Diffusion diffusion = Diffusion::steps;  // steps or sweep
  bool sweep_where_exact = false;           // diffusion=sweep_where_exact: sweep the frames where it is exact
  float lambda_alpha = 1.0f, lambda_beta = 0.05f, lambda_gamma = 0.1f;
  FieldDiffusion field_diffusion = FieldDiffusion::nonphysical;
  Profile profile = Profile::none;
  float exponential_p = 3.0f, power_p = 0.3f;
  float weight_z = 1.0f, weight_n = 1.0f;
  bool weld_vertices = true;
  uint32_t max_per_pixel = 64;
  uint64_t initial_nodes_per_pixel = 8;
  SortMethod sort = SortMethod::automatic;
  Storage storage = Storage::linearized;
  SlotFill fill = SlotFill::automatic;  // storage=linearized or arrays (list_length_pass.h)
  // storage=arrays_when_even (storage is linearized then): each frame fills
  // per-pixel arrays where the last frame's lists were even enough
  // (records.h, kMostSlotsPerFragment), else runs the counting pass.
  bool arrays_where_even = false;
  bool flat_color_records = true;  // unlit scenes, lit ones with ranged(): no colour in the fill record
  float normal_variation_scale = 10.0f;
  float focus_region = 1.0f;  // modulation=ray_distance: eq. 1's focusRegion, in view-space units
  bool measure_accuracy = false;
  double accuracy_footprints = 1.5;

  bool linearized() const { return storage == Storage::linearized; }
  bool arrays() const { return storage == Storage::arrays; }
  bool may_fill_arrays() const { return arrays() || arrays_where_even; }
  // Whether each pixel's fill records are contiguous and the host knows
  // every pixel's count before the sort (linearized: from the counting pass;
  // arrays: the fill's cursors, read back).
  bool ranged() const { return linearized() || arrays(); }
  // storage=linearized or arrays taking its slots by framebuffer fetch (fill, resolved on this device).
  bool fetches_cursors() const { return ranged() && fills_by_framebuffer_fetch(fill); }
  bool heuristic() const { return neighbors != NeighborSearch::triangle_index; }
  // The modes that search neighbours and diffuse fields (carnecky2013 section 5).
  bool diffused() const { return uses_beta() || uses_gamma(); }
  // The purely local baselines: an opacity per fragment from the fill.
  bool purely_local() const { return modulation == Modulation::angle || modulation == Modulation::normal_variation; }
  bool uses_beta() const { return modulation == Modulation::silhouette || modulation == Modulation::silhouette_halo; }
  bool uses_gamma() const { return modulation == Modulation::halo || modulation == Modulation::silhouette_halo; }
  // Whether anything reads a fragment's normal, depth slopes and local
  // opacity: the heuristic searches (eq. 1-2) and the purely local
  // baselines. The triangle-index search and plain blending do not, so the
  // fill leaves them out and the sort stores the triangle's vertices instead.
  bool records_surface() const { return (diffused() && heuristic()) || purely_local(); }
  bool stores_triangle_vertices() const { return diffused() && !heuristic(); }
  // The steps of skip_converged (worklist.glsl); the sweeps need no tracking.
  bool tracks_convergence() const { return diffused() && skip_converged && diffusion == Diffusion::steps; }
  // Whether `iterations` steps of eq. 9 take every value of 1 down to 0 or
  // below for each field used, so that the steps' result is the fixed point
  // wherever alpha cannot move (Diffusion).
  bool sweep_reaches_steps() const;
  // Eq. 9's values along a path from a field of 1: F(0) = 1, F(d) =
  // F(d - 1) - lambda in float, as the shaders subtract, for d < count.
  static std::vector<float> values_from_one(float lambda, uint32_t count);
  // Whether the sweeps may run at all (some frame may still need the steps:
  // one_alpha). They reach eq. 9's fixed point: never with eq. 8.
  bool may_sweep() const {
    return diffused() && field_diffusion == FieldDiffusion::nonphysical &&
           (diffusion == Diffusion::sweep || sweep_where_exact);
  }
};

Settings settings_from(const ParamSet& params);
// The explicit choice this device cannot run (fill=framebuffer_fetch without
// the extension), or "": the harness skips such a run.
std::string missing_device_feature(const Settings& settings, const DeviceProfile& device);
std::unique_ptr<Technique> make_illustration_buffer(const Settings& settings);
// GPU storage of a frame of `content` (TechniqueDescriptor::storage_need).
StorageNeed storage_need(const Settings& settings, const FrameContent& content);

}  // namespace oit::illustration_buffer
