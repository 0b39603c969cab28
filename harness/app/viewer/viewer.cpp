#include "harness/app/viewer/viewer.h"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "harness/app/sweep.h"
#include "harness/app/viewer/param_editor.h"
#include "scenes/cameras.h"
#include "harness/gl/check.h"
#include "harness/toolkit/passes.h"
#include "harness/gl/shader_program.h"
#include "scenes/scene_library.h"

namespace oit {
namespace {

std::string background_text(const glm::vec3& c) {
  return real_text(c.r) + "," + real_text(c.g) + "," + real_text(c.b);
}

}  // namespace

Viewer::Viewer(GlfwWindowContext& window, const ViewOptions& options)
    : window_(window), registry_(builtin_techniques()), options_(options) {
  parse_size(size_for(options.size, window_.device()), width_, height_);
  background_ = parse_background(options.background);
  sweep_file_ = options.sweep_file;
  sweep_csv_ = options.sweep_csv;
  display_ = options.display == "reference" ? Display::reference
             : options.display == "error"   ? Display::error
             : options.display == "list_length" ? Display::list_length
             : options.display == "diagnostic"  ? Display::diagnostic
                                                : Display::image;
  diagnostic_name_ = options.diagnostic;
  show_ = options.show == "b" ? Show::b : options.show == "split" ? Show::split : Show::a;

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini in the user's directory
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForOpenGL(window_.window(), true);
  ImGui_ImplOpenGL3_Init("#version 450");

  // Command-line mistakes are errors (as in `render`); in the panel they
  // become messages.
  // Scoped and checked as render's are (sweep.h).
  const RawParams scene_params = one_value_scene_params(options.scene_sets, options.scene);
  if (std::string m = open_scene(options.scene, scene_params); !m.empty()) throw std::runtime_error(m);
  scene_input_ = options.scene;
  scene_wanted_ = scene_params;

  const CameraSpec camera = parse_camera_spec(options.camera);
  preset_kind_ = camera.kind == CameraSpec::Kind::scene_default ? 0
                 : camera.kind == CameraSpec::Kind::max_list    ? 2
                                                                : 1;
  preset_count_ = int(camera.count);
  preset_seed_ = int(camera.seed);
  preset_index_ = int(camera.index);  // a whole set starts at its view 0
  if (std::string m = apply_camera_preset(preset_spec()); !m.empty()) throw std::runtime_error(m);

  const ClockKind clock = window_.device().software ? ClockKind::wall : ClockKind::gl;
  a_ = std::make_unique<Slot>(LiveTechnique(registry_, window_.device(), clock));
  b_ = std::make_unique<Slot>(LiveTechnique(registry_, window_.device(), clock));
  reference_ = std::make_unique<LiveTechnique>(registry_, window_.device(), ClockKind::wall);
  // As in bench: techniques under test use the scene rectangle as asked,
  // the reference never.
  const bool scene_rect = parse_on_off("--scene-rect", options.scene_rect);
  a_->live.set_scene_rect(scene_rect);
  b_->live.set_scene_rect(scene_rect);
  reference_->set_scene_rect(false);
  a_->wanted_id = options.technique;
  a_->wanted_params =
      one_value_technique_params(options.sets, {&registry_.get(options.technique)}, registry_).front();
  configure(*a_);
  if (!a_->message.empty()) throw std::runtime_error(a_->message);
  compare_ = !options.compare.empty();
  b_->wanted_id = compare_ ? options.compare : options.technique;
  b_->wanted_params =
      one_value_technique_params(options.compare_sets, {&registry_.get(b_->wanted_id)}, registry_).front();
  if (compare_) {
    configure(*b_);
    if (!b_->message.empty()) throw std::runtime_error(b_->message);
  }
  display_target_ = std::make_unique<RenderTarget>(width_, height_);
  Texture texture = make_texture_2d(GL_RGBA8, width_, height_);
  Framebuffer framebuffer = make_target_framebuffer({&texture}, "viewer: display framebuffer (RGBA8)");
  encoder_ = std::make_unique<DisplayEncoding>(
      DisplayEncoding{build_compute_program("shaders/display_srgb.comp"), std::move(texture), std::move(framebuffer)});
}

Viewer::~Viewer() {
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
}

// ---- scene and camera -------------------------------------------------

std::string Viewer::open_scene(const std::string& spec, const RawParams& params) {
  try {
    auto scene = std::make_unique<Scene>(load_scene(spec, params));
    auto gpu = std::make_unique<SceneGpu>(*scene);  // refers to *scene: both live together
    gl_check("uploading scene " + spec);
    scene_gpu_ = std::move(gpu);
    scene_ = std::move(scene);
    scene_spec_ = spec;
    scene_params_ = params;
    ++scene_generation_;
    return "";
  } catch (const std::exception& e) {
    drain_gl_errors();
    return e.what();
  }
}

std::string Viewer::preset_spec() const {
  if (preset_kind_ == 0) return "default";
  const std::string set = std::to_string(preset_count_) + ":" + std::to_string(preset_seed_);
  if (preset_kind_ == 2) return "max_list:" + set;
  return "random:" + set + "@" + std::to_string(preset_index_);
}

std::string Viewer::apply_camera_preset(const std::string& spec) {
  try {
    // max_list renders the scene from every viewpoint of its set: the same
    // choice (and probe size) as `render --camera max_list`.
    const Camera camera = resolve_camera(*scene_gpu_, spec);
    orbit_ = OrbitCamera(camera, scene_->bounds());
    return "";
  } catch (const std::exception& e) {
    return e.what();
  }
}

glm::mat4 Viewer::projection() const { return orbit_.camera().projection(float(width_) / float(height_)); }

SceneFacts Viewer::facts() const { return {scene_->triangle_count(), scene_->object_count, true}; }

// ---- techniques -------------------------------------------------------

void Viewer::configure(Slot& slot) {
  slot.message =
      slot.live.configure(slot.wanted_id, slot.wanted_params, facts(), scene_gpu_->shading(), width_, height_);
  if (slot.message.empty()) slot.render_error.clear();
}

void Viewer::render_slot(Slot& slot) {
  if (!slot.live.ready() || !slot.render_error.empty()) return;
  try {
    slot.live.render(*scene_gpu_, orbit_.camera().view, projection(), background_);
  } catch (const std::exception& e) {
    drain_gl_errors();
    slot.render_error = e.what();
  }
}

// ---- output -----------------------------------------------------------

void Viewer::encode_for_display(GLuint source_texture) {
  glUseProgram(encoder_->program.id());
  glBindTextureUnit(0, source_texture);
  glBindImageTexture(0, encoder_->texture.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
  glDispatchCompute(GLuint(width_ + 7) / 8, GLuint(height_ + 7) / 8, 1);
  glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT);
}

void Viewer::draw_scene_area(int framebuffer_height) {
  // The harness's images are linear; the scene area shows them as the PNG
  // writer writes them (sRGB-encoded, opaque), pixel for pixel at 1:1: a
  // compute pass encodes into RGBA8, which is copied without conversion
  // whatever the window's own framebuffer format.
  const int top = framebuffer_height - height_;  // GL rows count from the bottom
  auto show = [&](GLuint source_texture, int x0, int x1) {
    encode_for_display(source_texture);
    glBlitNamedFramebuffer(encoder_->framebuffer.id(), 0, x0, 0, x1, height_, x0, top, x1, top + height_,
                           GL_COLOR_BUFFER_BIT, GL_NEAREST);
  };
  if (display_ != Display::image) return show(display_target_->color.id(), 0, width_);
  const Slot& first = shown_slot();
  if (first.live.ready()) show(first.live.target().color.id(), 0, width_);
  if (compare_ && show_ == Show::split && b_->live.ready()) show(b_->live.target().color.id(), split_column(), width_);
}

void Viewer::handle_mouse() {
  const ImGuiIO& io = ImGui::GetIO();
  if (io.WantCaptureMouse) return;
  const ImVec2 p = io.MousePos;
  const bool inside = p.x >= 0 && p.y >= 0 && p.x < float(width_) && p.y < float(height_);
  const float h = float(height_);
  // Drags that started in the scene area keep going outside it.
  const bool left = ImGui::IsMouseDragging(ImGuiMouseButton_Left, 0.0f);
  const bool pan = ImGui::IsMouseDragging(ImGuiMouseButton_Right, 0.0f) ||
                   ImGui::IsMouseDragging(ImGuiMouseButton_Middle, 0.0f) || (left && io.KeyShift);
  const bool clicked_inside = [&] {
    for (int b = 0; b < 3; ++b) {
      const ImVec2 c = io.MouseClickedPos[b];
      if (io.MouseDown[b] && c.x >= 0 && c.y >= 0 && c.x < float(width_) && c.y < float(height_)) return true;
    }
    return false;
  }();
  if (clicked_inside && (io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f)) {
    if (pan) orbit_.pan(io.MouseDelta.x, io.MouseDelta.y, h);
    else if (left) orbit_.orbit(io.MouseDelta.x, io.MouseDelta.y, h);
  }
  if (inside && io.MouseWheel != 0.0f) orbit_.zoom(io.MouseWheel);
}

void Viewer::save_screenshot(const std::string& path) {
  // The whole window as shown (scene area + panel), from the back buffer
  // before it is swapped.
  int fb_width = 0, fb_height = 0;
  glfwGetFramebufferSize(window_.window(), &fb_width, &fb_height);
  std::vector<uint8_t> bytes(size_t(fb_width) * size_t(fb_height) * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, fb_width, fb_height, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
  gl_check("reading the window for a screenshot");
  Image image{fb_width, fb_height, std::vector<float>(bytes.size())};
  for (size_t i = 0; i < bytes.size(); ++i) image.rgba[i] = float(bytes[i]) / 255.0f;
  // The window is opaque whatever alpha its framebuffer holds.
  for (size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 1.0f;
  write_image(image, path, PngEncoding::raw);  // display bytes already; bottom-up rows, written top row first
  std::printf("screenshot %s: %dx%d window; scene area x=0 y=0 w=%d h=%d (from the top-left)\n", path.c_str(),
              fb_width, fb_height, width_, height_);
  std::fflush(stdout);
}

ViewConfig Viewer::config_of(const Slot& slot) const {
  ViewConfig c;
  c.technique = slot.live.id();
  c.params = slot.live.params();
  c.scene = scene_spec_;
  c.scene_params = scene_params_;
  c.width = width_;
  c.height = height_;
  c.camera = preset_spec();
  c.background = background_text(background_);
  c.scene_rect = slot.live.scene_rect();
  return c;
}

void Viewer::add_to_sweep_file() {
  try {
    const std::string comment =
        orbit_.moved() ? "camera moved interactively in the viewer; bench uses its preset " + preset_spec() : "";
    append_to_sweep_file(sweep_file_, bench_command_line(config_of(*a_), sweep_csv_), comment);
    if (compare_ && b_->live.ready()) append_to_sweep_file(sweep_file_, bench_command_line(config_of(*b_), sweep_csv_));
    output_message_ = "appended to " + sweep_file_;
  } catch (const std::exception& e) {
    output_message_ = e.what();
  }
}

// ---- loop -------------------------------------------------------------

int Viewer::run() {
  for (int frame = 0; !window_.should_close(); ++frame) {
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    int fb_width = 0, fb_height = 0;
    glfwGetFramebufferSize(window_.window(), &fb_width, &fb_height);

    handle_mouse();
    // Space toggles A/B (when no text field has the keyboard).
    const bool space = glfwGetKey(window_.window(), GLFW_KEY_SPACE) == GLFW_PRESS;
    if (space && !space_was_down_ && compare_ && !ImGui::GetIO().WantCaptureKeyboard)
      show_ = show_ == Show::a ? Show::b : Show::a;
    space_was_down_ = space;
    draw_panel(fb_width, fb_height);

    render_slot(*a_);
    if (compare_) render_slot(*b_);
    update_diagnostics();

    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fb_width, fb_height);
    glClearColor(0.12f, 0.12f, 0.14f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    draw_scene_area(fb_height);
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());

    const bool last = options_.frames > 0 && frame + 1 >= options_.frames;
    if (screenshot_requested_) {
      screenshot_requested_ = false;
      try {
        save_screenshot(screenshot_path_);
        output_message_ = "saved " + screenshot_path_;
      } catch (const std::exception& e) {
        output_message_ = e.what();
      }
    }
    if (last && !options_.screenshot.empty()) save_screenshot(options_.screenshot);
    window_.swap_buffers_and_poll();
    if (last) break;
  }
  // A scripted run (--frames) must not pass with a technique that failed.
  for (const Slot* slot : {a_.get(), compare_ ? b_.get() : nullptr}) {
    if (slot && !slot->render_error.empty()) {
      std::fprintf(stderr, "oitbench view: %s failed: %s\n", slot->live.id().c_str(), slot->render_error.c_str());
      return 1;
    }
  }
  return 0;
}

}  // namespace oit
