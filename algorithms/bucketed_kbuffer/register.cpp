// The descriptor of the bucketed k-buffer: parameters, stages, support check.
#include <string>

#include "harness/toolkit/fragment_pool.h"
#include "harness/toolkit/technique.h"
#include "algorithms/bucketed_kbuffer/choices.h"
#include "algorithms/bucketed_kbuffer/transfer_functions.h"

namespace oit {

std::unique_ptr<Technique> make_bucketed_kbuffer(const ParamSet& params);  // bucketed_kbuffer.cpp

void register_technique_bucketed_kbuffer(TechniqueRegistry& registry) {
  registry.add({
      .id = "bucketed_kbuffer",
      .display_name = "Bucketed k-buffer (mean curvature transparency)",
      .paper = "Murray, Baril, Granier 2016, Shape depiction for transparent objects with bucketed k-buffer",
      .params = {
          ParamSpec::integer_or_auto("k", "16", 1, 64,
                                     "slots per pixel: the k nearest fragments are kept; auto = the view's depth "
                                     "complexity, counted every frame (capped by auto_k_memory_mb)"),
          bkb::kBucketModes.spec("buckets", bkb::BucketMode::automatic,
                                 "how store (and, with neighbor_search=bucket, the neighbour query) finds a shape's "
                                 "fragments: one hashed bucket (on), all fragments (off: brute force query, hashed "
                                 "store), or each pixel's whole list as its one bucket (single, one-object scenes "
                                 "only: no bucket pass, no hash look-ups); auto = single on a one-object scene, "
                                 "else on"),
          bkb::kNeighborSearches.spec(
              "neighbor_search", bkb::NeighborSearch::merge,
              "neighbour query: walk the two sorted lists from the depth-nearest fragment of the shape until the "
              "depth difference alone exceeds the best score (merge), or scan the bucket or list that buckets "
              "selects (bucket); both find the same links"),
          ParamSpec::boolean("reverse_check", true,
                             "keep a link only if no other fragment of the pixel is closer to the candidate "
                             "(carnecky2013 Algorithm 2, murray2016 Figure 5); false links every best candidate, "
                             "mutual or not"),
          bkb::kColorTransfers.spec(
              "color_transfer", bkb::ColorTransfer::mean_curvature_shading,
              "1D colour transfer function of kappa: murray2016 Figure 6(a), 6(b), or colour unchanged"),
          bkb::kOpacityTransfers.spec("opacity_transfer", bkb::OpacityTransfer::front_focus,
                                      "2D opacity transfer function of |kappa| and depth: murray2016 Figure 7/8(a), "
                                      "7/8(b), or alpha unchanged"),
          ParamSpec::path("color_transfer_file", "",
                          "colour transfer function from a file, overriding color_transfer: text (m, r g b, kappa m "
                          "or kappa r g b per line) or PNG (first row, kappa -1 .. 1); see the technique README"),
          ParamSpec::path("opacity_transfer_file", "",
                          "opacity transfer function from a file, overriding opacity_transfer: text grid or PNG, "
                          "rows = depth (first/top = near), columns = |kappa| (first/left = 0); see the technique "
                          "README"),
          bkb::kDepthBits.spec("depth_bits", 16,
                               "depth bits of the 32-bit key; the shape id gets the rest (24: at most 256 objects)"),
          ParamSpec::real("curvature_scale", 1.0, 1e-3, 1e3,
                          "kappa = tanh(curvature_scale * (k1 + k2)), curvatures in 1 / scene units"),
          ParamSpec::boolean("measure_accuracy", false,
                             "keep links, curvatures and surface id/uv for counters(): link checksum, link "
                             "precision/recall, kappa error on analytic scenes"),
          bkb::kSlotLayouts.spec(
              "slot_layout", bkb::SlotLayout::full,
              "per slot: Z, B, colour, normal and a kappa word, stylized in a pass of its own (full, 20 bytes), or "
              "murray2016's 128 bits, stylized in the neighbour pass (paper, 16 bytes: the same image, no kappa "
              "kept: no diagnostic images or link counts unless measure_accuracy)"),
          ParamSpec::integer("auto_k_memory_mb", 1024, 1, 1 << 20,
                             "k=auto only: most MiB of slot storage (20 bytes per slot, 16 with slot_layout=paper, "
                             "48 with measure_accuracy); k is capped to fit")},
      .stages = {"count", "clear", "fill", "sort", "bucket", "store", "neighbors", "stylize", "compose"},
      .quality_sweep = {{"k", {"1", "2", "4", "8", "16", "32", "64"}}, {"neighbor_search", {"bucket", "merge"}}},
      .adaptive_switches = {{"buckets_auto",
                              "on a one-object scene skips the bucket pass (no hash tables) and searches each whole "
                              "list as the single bucket, without hash look-ups or shape tests",
                              {{"buckets", "auto"}}, {{"buckets", "on"}}},
                             {"neighbor_merge",
                              "walks both sorted lists from the depth-nearest fragment and stops where the depth "
                              "difference alone exceeds the best score, instead of scoring every fragment of the "
                              "bucket (and of its own bucket for the reverse check); the same links",
                              {{"neighbor_search", "merge"}}, {{"neighbor_search", "bucket"}}},
                             {"k_auto", "sizes k from the view's depth complexity (a counting pass) instead of the "
                                        "worst-case constant 64",
                              {{"k", "auto"}}, {{"k", "64"}}}},
      .extra_support_check = [](const ParamSet& params, const SceneFacts& scene, const DeviceProfile&) -> std::string {
        const int depth_bits = params.choice("depth_bits", bkb::kDepthBits);
        const uint32_t limit = 1u << (32 - depth_bits);
        if (scene.objects > limit)
          return "bucketed_kbuffer: depth_bits=" + std::to_string(depth_bits) + " leaves room for " +
                 std::to_string(limit) + " shape ids; the scene has " + std::to_string(scene.objects) + " objects";
        if (params.choice("buckets", bkb::kBucketModes) == bkb::BucketMode::single && scene.objects > 1)
          return "bucketed_kbuffer: buckets=single takes each pixel's list as one shape, and the scene has " +
                 std::to_string(scene.objects) + " objects: use buckets=on (or auto)";
        return "";
      },
      .resolve = [](const ParamSet& requested, const ResolveInput& input) -> RawParams {
        // objects 0: built without a scene (a test's renderer): the frame decides.
        if (requested.choice("buckets", bkb::kBucketModes) != bkb::BucketMode::automatic || input.scene.objects == 0)
          return {};
        return {{"buckets", input.scene.objects == 1 ? "single" : "on"}};
      },
      // murray2016 searches each fragment's bucket, buckets always on, in
      // 128 bits per fragment (section 6).
      .paper_preset = {{"neighbor_search", "bucket"}, {"buckets", "on"}, {"slot_layout", "paper"}},
      .create = make_bucketed_kbuffer,
      .storage_need = [](const ParamSet& params, const FrameContent& content) {
        const bool measure = params.boolean("measure_accuracy");
        const bool paper = params.choice("slot_layout", bkb::kSlotLayouts) == bkb::SlotLayout::paper;
        const uint64_t slots = content.pixels() * fragment_pool::slots_per_pixel(content, params, 64);
        return StorageNeed{slots * (measure ? 16 : 4), slots * (measure ? 48 : paper ? 16 : 20) + content.pixels() * 4};
      },
      // Links reach the 4 adjacent pixels, and a link is kept only when the
      // neighbour's own search finds the pixel back (reverse check).
      .tile_halo = [](const ParamSet&) { return 2; },
  });
}

}  // namespace oit
