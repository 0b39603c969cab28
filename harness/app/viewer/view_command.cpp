#include "harness/app/viewer/view_command.h"

#include <CLI/CLI.hpp>

#include <cstdlib>
#include <stdexcept>

#include "harness/app/sweep_cli.h"
#include "harness/app/viewer/viewer.h"
#include "harness/gl/glfw_window.h"

namespace oit {

CLI::App* add_view_command(CLI::App& app, ViewOptions& o) {
  auto* view = app.add_subcommand(
      "view", "interactive viewer (needs a display; under xvfb-run with --frames N --screenshot for scripts)");
  view->add_option("--technique,-t", o.technique, "technique A (see `list`)");
  view->add_option("--set", o.sets, "technique A parameter key=value (repeatable)");
  add_scene_cli_options(view, o.scene, o.scene_sets);
  view->add_option("--size", o.size,
                   "WIDTHxHEIGHT of the rendered image (larger than bench's 256x256: an image to look at in a "
                   "window, and murray2016 Fig. 10's size, which software GL renders in screen tiles)");
  view->add_option("--background", o.background, "r,g,b (linear)");
  view->add_option("--camera", o.camera, "preset: default, random:N:SEED[@I] or max_list[:N:SEED]");
  view->add_option("--compare", o.compare, "technique B for the A/B comparison");
  view->add_option("--compare-set", o.compare_sets, "technique B parameter key=value (repeatable)");
  view->add_option("--show", o.show, "a, b or split")->check(oit::one_of({"a", "b", "split"}));
  view->add_option("--display", o.display,
                   "image, reference, error, list_length or diagnostic (a per-pixel field the technique offers)")
      ->check(oit::one_of({"image", "reference", "error", "list_length", "diagnostic"}));
  view->add_option("--diagnostic", o.diagnostic,
                   "with --display diagnostic: which of the technique's fields (default: its first)");
  view->add_option("--frames", o.frames, "render N frames, then exit (0: until the window closes)")
      ->check(CLI::Range(0, 1000000));
  view->add_option("--screenshot", o.screenshot, "PNG of the window written after the last frame");
  view->add_option("--sweep-file", o.sweep_file, "text file that 'Add to sweep file' appends bench command lines to");
  view->add_option("--scene-rect", o.scene_rect,
                   "on (default): confine techniques A and B to the scene's projected rectangle; off: full image")
      ->check(oit::one_of({"on", "off"}));
  view->add_option("--sweep-csv", o.sweep_csv, "the --csv of the appended bench command lines");
  return view;
}

int run_view(const CommonOptions& common, const ViewOptions& options) {
  // GLFW would fail too, but later and with a terser message; say what to
  // do instead before touching it.
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((!display || !*display) && (!wayland || !*wayland)) {
    throw std::runtime_error(
        "oitbench view needs a display, and DISPLAY is not set. Without one, use `oitbench render` (one image) or "
        "`oitbench bench` (timings and errors), or run the viewer on a virtual X server: "
        "xvfb-run -a oitbench view ... --frames N --screenshot out.png");
  }
  if (common.device != "auto") {
    throw std::invalid_argument("oitbench view renders with the window's GL (the display's device); --device " +
                                common.device + " applies to the headless commands only");
  }
  int width = 0, height = 0;
  parse_size(options.size, width, height);
  GlfwWindowContext window(width + Viewer::kPanelWidth, std::max(height, Viewer::kMinHeight), "oitbench view");
  Viewer viewer(window, options);
  return viewer.run();
}

}  // namespace oit
