// `oitbench stats`: how many fragments a scene view produces and how they
// spread over the pixels (pastyrik2016 section 4.2: list lengths, the
// complexity coverage Psi, Fig. 10 heatmaps), without running a technique.
#include <cstdio>
#include <string>

#include "harness/app/commands.h"
#include "scenes/cameras.h"
#include "harness/run/complexity.h"
#include "scenes/scene_library.h"

namespace oit {
namespace {

std::string with_thousands(uint64_t value) {
  std::string digits = std::to_string(value), text;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) text += ',';
    text += digits[i];
  }
  return text;
}

void print_histogram(const DepthComplexity& c) {
  const auto bins = binned_histogram(list_length_histogram(c), 16);
  std::printf("histogram         list length: pixels\n");
  const double pixels = double(c.per_pixel.size());
  for (size_t i = 0; i < bins.size(); ++i) {
    char range[32];
    if (bins[i].first == bins[i].last) std::snprintf(range, sizeof range, "%u", bins[i].first);
    else std::snprintf(range, sizeof range, "%u-%u", bins[i].first, bins[i].last);
    std::printf("  %9s: %-10s (%5.1f%%)", range, with_thousands(bins[i].pixels).c_str(),
                100.0 * double(bins[i].pixels) / pixels);
    if (i % 4 == 3 || i + 1 == bins.size()) std::printf("\n");
  }
}

}  // namespace

int run_stats(const CommonOptions& common, const StatsOptions& options) {
  int width = 0, height = 0;
  parse_size(options.size, width, height);
  RawParams scene_params;
  for (const auto& s : options.scene_sets) parse_assignment(s, scene_params);
  const std::vector<std::string> cameras = expand_camera_spec(options.camera);

  auto context = create_headless_context(parse_device_choice(common.device), common.debug_gl);
  parse_size(size_for(options.size, context->device()), width, height);
  const Scene scene = load_scene(options.scene, scene_params);
  const SceneGpu gpu(scene);
  const float aspect = float(width) / float(height);
  std::printf("scene             %s%s%s\n", options.scene.c_str(), scene.params.empty() ? "" : " ",
              scene.params.c_str());
  std::printf("triangles         %s\nvertices          %s\nobjects           %s\nshading           %s\n",
              with_thousands(scene.triangle_count()).c_str(), with_thousands(scene.vertices.size()).c_str(),
              with_thousands(scene.object_count).c_str(), scene.lit ? "lit" : "unlit");
  std::printf("size              %dx%d\n", width, height);

  for (size_t view = 0; view < cameras.size(); ++view) {
    const CameraSpec spec = parse_camera_spec(cameras[view]);
    Camera camera;
    std::string chosen;
    if (spec.kind == CameraSpec::Kind::max_list) {
      const ChosenViewpoint best = choose_max_list_camera(gpu, spec);
      camera = best.camera;
      chosen = " (viewpoint random:" + std::to_string(spec.count) + ":" + std::to_string(spec.seed) + "@" +
               std::to_string(best.index) + ", longest list " + std::to_string(best.max_list) + " at 256x256)";
    } else {
      camera = camera_for_spec(scene, spec);
    }
    const DepthComplexity c = measure_depth_complexity(gpu, camera.view, camera.projection(aspect), width, height);
    std::printf("\ncamera            %s%s\n", cameras[view].c_str(), chosen.c_str());
    std::printf("fragments         %s\n", with_thousands(c.fragments).c_str());
    std::printf("covered pixels    %s of %s (%.1f%%)\n", with_thousands(c.covered_pixels).c_str(),
                with_thousands(c.per_pixel.size()).c_str(), 100.0 * double(c.covered_pixels) / double(c.per_pixel.size()));
    std::printf("depth complexity  max %u, mean %.3f over all pixels, %.3f over covered pixels\n", c.max, c.mean,
                c.covered_pixels ? double(c.fragments) / double(c.covered_pixels) : 0.0);
    std::printf("psi               %.4f (share of all pixels whose list is longer than 2/3 of %u)\n", c.psi, c.max);
    print_histogram(c);
    if (!options.heatmap.empty()) {
      const std::string path = cameras.size() > 1 ? per_view_path(options.heatmap, view) : options.heatmap;
      write_image(with_colour_bar(list_length_heatmap(c), list_length_scale(c)), path);
      std::printf("heatmap           %s (%dx%d, viridis 0 .. %u fragments; colour bar in the %d rows below)\n",
                  path.c_str(), width, height, c.max, kColourBarHeight);
    }
  }
  return 0;
}

}  // namespace oit
