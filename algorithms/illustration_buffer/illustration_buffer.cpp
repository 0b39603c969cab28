// illustration_buffer: the registry entry and the parameter schema. The
// technique itself is in technique.cpp and its stages (*_stage.h); see README.md.
#include "algorithms/illustration_buffer/settings.h"


namespace oit {
namespace illustration_buffer {
namespace {

const Choices<NeighborSearch> kNeighborSearches{{NeighborSearch::heuristic, "heuristic"},
                                                 {NeighborSearch::heuristic_merge, "heuristic_merge"},
                                                 {NeighborSearch::triangle_index, "triangle_index"}};
const Choices<Modulation> kModulations{{Modulation::none, "none"},
                                       {Modulation::silhouette, "silhouette"},
                                       {Modulation::halo, "halo"},
                                       {Modulation::silhouette_halo, "silhouette_halo"},
                                       {Modulation::angle, "angle"},
                                       {Modulation::normal_variation, "normal_variation"},
                                       {Modulation::ray_distance, "ray_distance"}};
const Choices<SortMethod> kSorts{{SortMethod::automatic, "auto"}, {SortMethod::array, "array"},
                                 {SortMethod::dynamic, "dynamic"}, {SortMethod::static_arrays, "static_arrays"}};
// sort=auto takes the dynamic sort up to this longest list (on a software
// rasterizer, linked lists), the array's ranks beyond.
constexpr uint32_t kLongestDynamicList = 4;
const Choices<Storage> kStorages{{Storage::automatic, "auto"},
                                  {Storage::linked, "linked"},
                                  {Storage::linearized, "linearized"},
                                  {Storage::arrays, "arrays"},
                                  {Storage::arrays_when_even, "arrays_when_even"}};
const Choices<Diffusion> kDiffusions{{Diffusion::automatic, "auto"},
                                     {Diffusion::steps, "steps"},
                                     {Diffusion::sweep, "sweep"},
                                     {Diffusion::sweep_where_exact, "sweep_where_exact"}};
// flat_color_records: true and false, or auto (true on a software
// rasterizer, false on a GPU).
const Choices<int> kFlatColorRecords{{-1, "auto"}, {1, "true"}, {0, "false"}};
const Choices<FieldDiffusion> kFieldDiffusions{{FieldDiffusion::nonphysical, "nonphysical"},
                                               {FieldDiffusion::homogeneous, "homogeneous"}};
const Choices<Profile> kProfiles{{Profile::none, "none"}, {Profile::exponential, "exponential"}, {Profile::power, "power"}};

// A resolved choice; throws for an `auto` the resolution rule did not resolve.
template <typename E>
E resolved(const ParamSet& p, const std::string& name, const Choices<E>& table) {
  if (p.choice(name) == "auto")
    throw std::logic_error("illustration_buffer: " + name + "=auto reached the technique unresolved");
  return p.choice(name, table);
}

}  // namespace

bool Settings::sweep_reaches_steps() const {
  // The value after n steps from 1 is 1 - lambda - ... - lambda (n times, in
  // float, as the shader computes it); a field is carried to its end when
  // step iterations + 1 would be at or below 0, the unfixed fields' start.
  const auto reaches = [&](float lambda) { return values_from_one(lambda, uint32_t(iterations) + 2).back() <= 0.0f; };
  return (!uses_beta() || reaches(lambda_beta)) && (!uses_gamma() || reaches(lambda_gamma));
}

std::vector<float> Settings::values_from_one(float lambda, uint32_t count) {
  std::vector<float> values(count);
  float value = 1.0f;
  for (float& v : values) {
    v = value;
    value -= lambda;
  }
  return values;
}

Settings settings_from(const ParamSet& p) {
  Settings s;
  s.neighbors = p.choice("neighbors", kNeighborSearches);
  s.modulation = p.choice("modulation", kModulations);
  s.adaptive_alpha = p.boolean("adaptive_alpha");
  s.iterations = int(p.integer("iterations"));
  s.skip_converged = p.boolean("skip_converged");
  s.diffusion_tolerance = float(p.real("diffusion_tolerance"));
  const Diffusion diffusion = resolved(p, "diffusion", kDiffusions);
  s.diffusion = diffusion == Diffusion::sweep ? Diffusion::sweep : Diffusion::steps;
  s.sweep_where_exact = diffusion == Diffusion::sweep_where_exact;
  s.sort = p.choice("sort", kSorts);
  s.fill = p.choice("fill", kSlotFills);
  const Storage storage = resolved(p, "storage", kStorages);
  s.storage = storage == Storage::arrays_when_even ? Storage::linearized : storage;
  s.arrays_where_even = storage == Storage::arrays_when_even;
  s.flat_color_records = resolved(p, "flat_color_records", kFlatColorRecords) == 1;
  s.normal_variation_scale = float(p.real("normal_variation_scale"));
  s.focus_region = float(p.real("focus_region"));
  s.lambda_alpha = float(p.real("lambda_alpha"));
  s.lambda_beta = float(p.real("lambda_beta"));
  s.lambda_gamma = float(p.real("lambda_gamma"));
  s.field_diffusion = p.choice("field_diffusion", kFieldDiffusions);
  s.profile = p.choice("profile", kProfiles);
  s.exponential_p = float(p.real("exponential_p"));
  s.power_p = float(p.real("power_p"));
  s.weight_z = float(p.real("weight_z"));
  s.weight_n = float(p.real("weight_n"));
  s.weld_vertices = p.boolean("weld_vertices");
  s.max_per_pixel = uint32_t(p.integer("max_per_pixel"));
  s.initial_nodes_per_pixel = uint64_t(p.integer("initial_nodes_per_pixel"));
  s.measure_accuracy = p.boolean("measure_accuracy");
  s.accuracy_footprints = p.real("accuracy_footprints");
  return s;
}

// preset=paper (README: Preset; the registry adds the parameter and applies
// these where the user set nothing): carnecky2013 as published. Its neighbour
// search (Algorithm 2, eq. 1-3 with w_z = w_n), its storage (linked lists,
// Algorithm 1), its sort (a local array, section 4.3), its diffusion
// (`iterations` synchronous steps of eq. 8-9 over every fragment, Fig. 9's
// first configuration: n = 20, lambda_alpha = 1, eq. 9 with lambda_beta =
// 0.05, lambda_gamma = 0.1, no profile), eq. 4's initial alpha, and the
// fill record with its colour.
const RawParams kPaperValues = {
    {"neighbors", "heuristic"},   {"modulation", "silhouette_halo"}, {"adaptive_alpha", "false"},
    {"iterations", "20"},         {"lambda_alpha", "1"},             {"lambda_beta", "0.05"},
    {"lambda_gamma", "0.1"},      {"field_diffusion", "nonphysical"}, {"profile", "none"},
    {"weight_z", "1"},            {"weight_n", "1"},                 {"storage", "linked"},
    {"sort", "array"},            {"diffusion", "steps"},            {"skip_converged", "false"},
    {"diffusion_tolerance", "0"}, {"flat_color_records", "false"}};

// The resolution rule (README: Device-dependent defaults), on the values
// after the paper preset: storage=auto: linked where sort=dynamic needs it;
// linearized where fill= asks for a ranged fill; else arrays_when_even on a
// software rasterizer and linked on a GPU. diffusion=auto:
// sweep_where_exact on a software rasterizer without a tolerance (a
// tolerance asks for the steps that stop small moves) and with eq. 9 (the
// sweeps reach its fixed point, never eq. 8's), steps elsewhere.
// flat_color_records=auto: true on a software rasterizer, false on a GPU.
// fill=auto, where the storage is ranged: framebuffer fetch where the
// device has it. sort=auto: the dynamic sort on a software rasterizer where
// the lists are linked and the view's longest holds at most
// kLongestDynamicList fragments (faster there:
// results/reference/illustration_buffer/README.md, Sort variants), else the
// paper's array; resolved once, so the CSV names the sort that ran.
RawParams resolve_parameters(const ParamSet& requested, const ResolveInput& input) {
  const bool software = input.device.software;
  RawParams resolved;
  const auto text = [&](const std::string& key) -> std::string { return requested.choice(key); };
  const SlotFill fill = requested.choice("fill", kSlotFills);
  Storage storage = kStorages.value(text("storage"));
  if (storage == Storage::automatic) {
    storage = kSorts.value(text("sort")) == SortMethod::dynamic ? Storage::linked
              : fill != SlotFill::automatic                    ? Storage::linearized
              : software                                       ? Storage::arrays_when_even
                                                               : Storage::linked;
    resolved["storage"] = kStorages.name(storage);
  }
  if (storage != Storage::linked) resolved["fill"] = kSlotFills.name(resolve_slot_fill(fill, input.device));
  if (kSorts.value(text("sort")) == SortMethod::automatic) {
    const uint32_t longest = input.content.longest_list;  // 0: not known (the viewer)
    const bool short_lists = longest > 0 && longest <= kLongestDynamicList;
    resolved["sort"] = kSorts.name(software && storage == Storage::linked && short_lists ? SortMethod::dynamic
                                                                                         : SortMethod::array);
  }
  if (kDiffusions.value(text("diffusion")) == Diffusion::automatic) {
    const bool may_sweep = requested.real("diffusion_tolerance") == 0.0 &&
                           requested.choice("field_diffusion", kFieldDiffusions) == FieldDiffusion::nonphysical;
    resolved["diffusion"] = software && may_sweep ? "sweep_where_exact" : "steps";
  }
  if (text("flat_color_records") == "auto") resolved["flat_color_records"] = software ? "true" : "false";
  return resolved;
}

}  // namespace illustration_buffer

void register_technique_illustration_buffer(TechniqueRegistry& registry) {
  registry.add({
      .id = "illustration_buffer",
      .display_name = "Illustration buffer (linked lists + geodesic neighbours, non-local opacity)",
      .paper = "Carnecky et al. 2013 (IEEE TVCG 19(5)); Pastyrik & Cmolik 2016 (CESCG)",
      .params = {
          illustration_buffer::kNeighborSearches.spec(
              "neighbors", illustration_buffer::NeighborSearch::triangle_index,
              "neighbour search: carnecky2013 Algorithm 2 (continuity measure eq. 1-3, mutual check), the same "
              "links found by a walk from the predicted depth in the depth-sorted list (heuristic_merge), or "
              "pastyrik2016 Algorithm 3 (triangles sharing a vertex index)"),
          illustration_buffer::kModulations.spec(
              "modulation", illustration_buffer::Modulation::silhouette_halo,
              "opacity modulation (carnecky2013 section 5): none = plain alpha blending (no neighbour search, no "
              "stylize), silhouette = beta field, halo = gamma field, or both; angle and normal_variation = the "
              "purely local baselines of carnecky2013 Fig. 11 (opacity from the angle between normal and view ray, "
              "or from the normal's screen-space variation); ray_distance = pastyrik2016 eq. 1, the opacity "
              "saturate(|depth - next depth| / focus_region) from the distance along the ray to the next sample "
              "(the farthest: 1; no neighbour search, no stylize)"),
          ParamSpec::boolean("adaptive_alpha", false, "initial alpha 1-(1-s)^(1/n) (eq. 5) instead of s (eq. 4)"),
          ParamSpec::integer("iterations", 20, 0, 1000,
                             "diffusion iterations of alpha (eq. 8) and beta/gamma (eq. 9, or eq. 8 with "
                             "field_diffusion=homogeneous)"),
          ParamSpec::boolean("skip_converged", true,
                             "diffuse only the pixels around fragments that changed in the previous iteration (the "
                             "others would recompute their value; exact with diffusion_tolerance 0)"),
          ParamSpec::real("diffusion_tolerance", 0.0, 0.0, 1.0,
                          "skip_converged (diffusion=steps; auto steps when this is above 0): a fragment whose fields "
                          "move by at most this keeps its value and does not wake its neighbours (0: the same image "
                          "as every fragment every iteration)"),
          illustration_buffer::kDiffusions.spec(
              "diffusion", illustration_buffer::Diffusion::automatic,
              "steps = `iterations` synchronous steps of eq. 8-9 (skip_converged applies); sweep = in-place "
              "raster-order sweeps in the four diagonal directions until no field moves, the same result where alpha cannot move "
              "(eq. 4, one alpha in the scene) and `iterations` steps carry beta and gamma to 0 (an error "
              "otherwise, and with a diffusion_tolerance); sweep_where_exact = sweep on the frames where that is exact, "
              "else steps (a software rasterizer's path); auto = sweep_where_exact on a software rasterizer "
              "when diffusion_tolerance is 0 and field_diffusion=nonphysical, else steps"),
          ParamSpec::real("lambda_alpha", 1.0, 0.0, 1.0,
                          "diffusion coefficient of alpha (eq. 8, normalised Laplacian)"),
          ParamSpec::real("lambda_beta", 0.05, 0.0, 1.0,
                          "silhouette field: decrement per step (eq. 9), or diffusion coefficient with "
                          "field_diffusion=homogeneous (eq. 8)"),
          ParamSpec::real("lambda_gamma", 0.1, 0.0, 1.0,
                          "halo field: decrement per step (eq. 9), or diffusion coefficient with "
                          "field_diffusion=homogeneous (eq. 8)"),
          illustration_buffer::kFieldDiffusions.spec(
              "field_diffusion", illustration_buffer::FieldDiffusion::nonphysical,
              "how beta and gamma spread from the boundaries (carnecky2013 5.4): nonphysical = eq. 9, u <- max(u, "
              "max(u_neighbours) - lambda_u); homogeneous = eq. 8 as for alpha, u <- u + lambda_u "
              "mean(u_neighbours - u) where u is not fixed (normalised Laplacian; lambda_u = 1: the neighbours' "
              "mean; carnecky2013 Fig. 9's third to fifth columns); diffusion=sweep needs nonphysical"),
          illustration_buffer::kProfiles.spec(
              "profile", illustration_buffer::Profile::none,
              "profile applied to beta and gamma before compositing: eq. 10 or eq. 11"),
          ParamSpec::real("exponential_p", 3.0, 0.01, 50.0, "p of the exponential profile (eq. 10)"),
          ParamSpec::real("power_p", 0.3, 0.01, 10.0, "p of the power profile (eq. 11)"),
          ParamSpec::real("weight_z", 1.0, 0.0, 1000.0, "w_z of the continuity measure (eq. 3; heuristic)"),
          ParamSpec::real("weight_n", 1.0, 0.0, 1000.0, "w_n of the continuity measure (eq. 3; heuristic)"),
          ParamSpec::boolean(
              "weld_vertices", true,
              "triangle_index: vertices at bitwise-equal positions count as one index (closes UV seams)"),
          illustration_buffer::kSorts.spec(
              "sort", illustration_buffer::SortMethod::automatic,
              "array = rank sort in a local array (carnecky2013 4.3); dynamic = insertion sort of the linked list in "
              "the buffers (pastyrik2016 Algorithm 2; storage=linked only); static_arrays = selection sort in three "
              "local arrays of 64 entries whatever the lists (pastyrik2016 3.2 and Fig. 7; max_per_pixel <= 64); "
              "auto = dynamic on a software rasterizer when the lists are linked and the view's longest has at most 4 "
              "fragments, else array; the same records either way"),
          illustration_buffer::kStorages.spec(
              "storage", illustration_buffer::Storage::automatic,
              "where the fill puts the records (the same records and image either way): linked = per-pixel "
              "linked lists in a pool sized from the previous frame (grown with a re-render on overflow; "
              "carnecky2013 Algorithm 1); linearized = a counting pass, "
              "then each pixel's contiguous range from the counts' prefix sum, exactly sized, filled in place "
              "(Knowles et al. 2012): no list walk in the sort, no global counter in the fill; arrays = no "
              "counting pass: per-pixel arrays of as many slots as the previous frame's longest list (first frame: "
              "initial_nodes_per_pixel), each fragment at its pixel's next slot, a longer list caught by its "
              "cursor and filled again with more slots; arrays_when_even = arrays on the frames after one whose "
              "slots would hold at most 4x its fragments and linearized on the others (a software rasterizer's "
              "path); auto = linked with sort=dynamic, linearized with fill=atomic or framebuffer_fetch, else "
              "arrays_when_even on a software rasterizer and linked on a GPU"),
          kSlotFills.spec(
              "fill", SlotFill::automatic,
              "storage=linearized or arrays: how a fragment takes its slot: atomic = an image atomic on its pixel's cursor; "
              "framebuffer_fetch = the cursor is the pixel's R32UI colour, read and incremented in primitive order "
              "(GL_EXT_shader_framebuffer_fetch); auto = framebuffer_fetch where the device has it"),
          illustration_buffer::kFlatColorRecords.spec(
              "flat_color_records", -1,
              "true = the fill stores no colour and the sort fetches the triangle's flat colour by triangle id: on "
              "unlit scenes, and on lit ones with storage=linearized or arrays (the record keeps the light factor "
              "instead of a list link; the same colour bit for bit); false, or lit scenes with storage=linked: the "
              "fill stores the float colour; auto = true on a software rasterizer, false on a GPU"),
          ParamSpec::real("normal_variation_scale", 10.0, 0.0, 1000.0,
                          "modulation=normal_variation: opacity = min(1, scale * |grad n|), grad n the view normal's "
                          "change per pixel (dFdx, dFdy)"),
          ParamSpec::real("focus_region", 1.0, 1e-6, 1e6,
                          "modulation=ray_distance: focusRegion of pastyrik2016 eq. 1, the view-space distance to the "
                          "next sample at which a sample becomes opaque"),
          ParamSpec::integer("max_per_pixel", 64, 1, 1024,
                             "sort array size; longer lists keep their nearest max_per_pixel fragments (counted)"),
          ParamSpec::integer("initial_nodes_per_pixel", 8, 1, 1024,
                             "storage=linked: first frame's pool per pixel; arrays: first frame's slots per pixel; either "
                             "grows (with a re-render) on overflow (storage=linearized sizes the pool exactly from its "
                             "counting pass)"),
          ParamSpec::boolean("measure_accuracy", false,
                             "record surface id and (u, v) per fragment and report neighbor_precision/recall "
                             "(16 B per fragment more; computed after the timed frames)"),
          ParamSpec::real("accuracy_footprints", 1.5, 0.5, 10.0,
                          "a link is correct when |du|, |dv| are within this many pixel footprints (fwidth(uv))")},
      // stylize_init sets the fields (carnecky2013 5.2-5.3); diffuse runs the
      // `iterations` steps of eq. 8-9 (iterations=1 times the paper's one solve step).
      // count: storage=linearized's counting pass and prefix sum; clear: storage=linked's.
      .stages = {"count", "clear", "fill", "sort", "neighbors", "stylize_init", "diffuse", "compose"},
      // The convergence tolerance trades error for time; the neighbour
      // searches change the links (heuristic and heuristic_merge find the same ones).
      .quality_sweep = {{"diffusion_tolerance", {"0.01", "0.001", "0"}},
                        {"neighbors", {"heuristic_merge", "heuristic", "triangle_index"}},
                        {"storage", {"linked", "linearized", "arrays"}}},
      // Approximate (the default): exact (float blend) only with modulation=none.
      .adaptive_switches = {{"diffusion_sweep",
                              "sweeps the fields in place to the fixed point instead of `iterations` steps where that "
                              "gives the same image (diffusion=auto; on a software rasterizer)",
                              {{"diffusion", "auto"}},
                              {{"diffusion", "steps"}}},
                             {"skip_converged",
                              "diffuses only the pixels around fragments that changed in the previous iteration",
                              {{"skip_converged", "true"}, {"diffusion", "steps"}},
                              {{"skip_converged", "false"}, {"diffusion", "steps"}}},
                             {"flat_color_records",
                              "stores no colour in the fill record (unlit scenes, and lit ones with contiguous ranges: "
                              "the light factor instead) and fetches each fragment's flat colour by triangle id in the "
                              "sort",
                              {{"flat_color_records", "true"}},
                              {{"flat_color_records", "false"}}}},
      .extra_support_check = [](const ParamSet& params, const SceneFacts& scene,
                                const DeviceProfile& device) -> std::string {
        const illustration_buffer::Settings s = illustration_buffer::settings_from(params);
        if (s.diffused() && s.neighbors == illustration_buffer::NeighborSearch::triangle_index && !scene.indexed)
          return "neighbors=triangle_index needs indexed geometry (shared vertex indices)";
        return illustration_buffer::missing_device_feature(s, device);
      },
      .resolve = illustration_buffer::resolve_parameters,
      .paper_preset = illustration_buffer::kPaperValues,
      .create = [](const ParamSet& params) {
        return illustration_buffer::make_illustration_buffer(illustration_buffer::settings_from(params));
      },
      .storage_need = [](const ParamSet& params, const FrameContent& content) {
        return illustration_buffer::storage_need(illustration_buffer::settings_from(params), content);
      },
      // A pixel's links reach the 4 adjacent pixels, and each diffusion
      // iteration carries values one link further (also when skip_converged
      // leaves fragments out: it computes the same iterations).
      .tile_halo = [](const ParamSet& params) {
        const illustration_buffer::Settings s = illustration_buffer::settings_from(params);
        return s.diffused() ? s.iterations + 2 : 0;
      },
  });
}

}  // namespace oit
