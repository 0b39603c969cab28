// The viewer's control panel: one ImGui window to the right of the scene
// area. Every control here acts on the Viewer state in viewer.cpp; widgets
// for parameters come from the schemas (param_editor.cpp).
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>

#include "harness/app/viewer/param_editor.h"
#include "harness/app/viewer/viewer.h"
#include "harness/run/runner.h"
#include "scenes/scene_library.h"

namespace oit {
namespace {

const ImVec4 kRed{1.0f, 0.45f, 0.4f, 1.0f};
const ImVec4 kGrey{0.65f, 0.65f, 0.65f, 1.0f};

void wrapped_colored(const ImVec4& colour, const std::string& text) {
  ImGui::PushStyleColor(ImGuiCol_Text, colour);
  ImGui::TextWrapped("%s", text.c_str());
  ImGui::PopStyleColor();
}

const ParamSchema* scene_schema(const std::string& id) {
  for (const auto& s : scene_library())
    if (s.id == id) return &s.params;
  return nullptr;  // a file: no parameters
}

std::string mib(uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f MiB", double(bytes) / (1024.0 * 1024.0));
  return text;
}

// The shown heatmap's colour bar, drawn like the PNGs' (heatmap.h): the
// colour map across the panel and the scale's ticks with their numbers.
void colour_bar(const ColourScale& scale, const std::string& what) {
  ImGui::TextWrapped("%s", what.c_str());
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const float margin = 16.0f, width = ImGui::GetContentRegionAvail().x - 2.0f * margin, height = 12.0f;
  const float left = origin.x + margin;
  // The window shows bytes as they are: viridis's sRGB values go straight in.
  auto colour = [](float t) {
    float srgb[3];
    viridis(t, srgb);
    return IM_COL32(int(std::lround(srgb[0] * 255.0f)), int(std::lround(srgb[1] * 255.0f)),
                    int(std::lround(srgb[2] * 255.0f)), 255);
  };
  constexpr int kSteps = 64;
  for (int i = 0; i < kSteps; ++i) {
    const float x0 = left + width * float(i) / kSteps, x1 = left + width * float(i + 1) / kSteps;
    const ImU32 a = colour(float(i) / kSteps), b = colour(float(i + 1) / kSteps);
    draw->AddRectFilledMultiColor({x0, origin.y}, {x1, origin.y + height}, a, b, b, a);
  }
  for (float tick : scale.ticks()) {
    const float x = left + scale.position(tick) * width;
    draw->AddLine({x, origin.y + height}, {x, origin.y + height + 3.0f}, IM_COL32_WHITE);
    const std::string label = scale.tick_label(tick);
    const float text_width = ImGui::CalcTextSize(label.c_str()).x;
    draw->AddText({std::clamp(x - 0.5f * text_width, origin.x, origin.x + 2.0f * margin + width - text_width),
                   origin.y + height + 4.0f},
                  IM_COL32_WHITE, label.c_str());
  }
  ImGui::Dummy({2.0f * margin + width, height + 6.0f + ImGui::GetTextLineHeight()});
}

}  // namespace

void Viewer::draw_panel(int framebuffer_width, int framebuffer_height) {
  ImGui::SetNextWindowPos(ImVec2(float(width_), 0.0f));
  ImGui::SetNextWindowSize(ImVec2(float(std::max(framebuffer_width - width_, 200)), float(framebuffer_height)));
  ImGui::Begin("oitbench view", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                                             ImGuiWindowFlags_NoCollapse);
  // Widgets leave room for their labels (long parameter names included).
  ImGui::PushItemWidth(-170.0f);
  ImGui::TextColored(kGrey, "%s", window_.device().renderer.c_str());
  ImGui::Text("%.1f frames/s", ImGui::GetIO().Framerate);
  if (ImGui::CollapsingHeader("Scene", ImGuiTreeNodeFlags_DefaultOpen)) panel_scene();
  if (ImGui::CollapsingHeader("Camera", ImGuiTreeNodeFlags_DefaultOpen)) panel_camera();
  if (ImGui::CollapsingHeader("Technique A", ImGuiTreeNodeFlags_DefaultOpen)) panel_technique(*a_, "A");
  if (compare_) ImGui::SetNextItemOpen(true, ImGuiCond_Once);  // --compare given
  if (ImGui::CollapsingHeader("A/B comparison")) {
    if (ImGui::Checkbox("compare with technique B", &compare_) && compare_ && !b_->live.ready()) configure(*b_);
    if (compare_) {
      int show = int(show_);
      ImGui::RadioButton("A", &show, 0);
      ImGui::SameLine();
      ImGui::RadioButton("B", &show, 1);
      ImGui::SameLine();
      ImGui::RadioButton("split (A | B)", &show, 2);
      show_ = Show(show);
      ImGui::TextColored(kGrey, "Space toggles A/B");
      if (show_ == Show::split) ImGui::SliderFloat("split", &split_, 0.0f, 1.0f, "%.2f");
      panel_technique(*b_, "B");
    }
  }
  // Timings and counters go below the scene area when it leaves room there
  // (the window is at least kMinHeight tall, the scene often much less):
  // in the panel they were cut off at the window's bottom.
  const bool below = width_ >= kBelowMinWidth && framebuffer_height - height_ >= kBelowMinHeight;
  auto timings = [&] {
    if (ImGui::CollapsingHeader("Timings and counters", ImGuiTreeNodeFlags_DefaultOpen)) {
      panel_timings(*a_, "A");
      if (compare_) panel_timings(*b_, "B");
    }
  };
  if (!below) timings();
  if (ImGui::CollapsingHeader("Diagnostics", ImGuiTreeNodeFlags_DefaultOpen)) panel_diagnostics();
  if (ImGui::CollapsingHeader("Output", ImGuiTreeNodeFlags_DefaultOpen)) panel_output();
  ImGui::PopItemWidth();
  ImGui::End();
  if (below) {
    ImGui::SetNextWindowPos(ImVec2(0.0f, float(height_)));
    ImGui::SetNextWindowSize(ImVec2(float(width_), float(framebuffer_height - height_)));
    ImGui::Begin("timings", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                                         ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoTitleBar);
    timings();
    ImGui::End();
  }

  // Labels over the split image, drawn by ImGui on top of the scene area.
  if (compare_ && show_ == Show::split && (display_ == Display::image || split_diagnostics())) {
    ImDrawList* draw = ImGui::GetForegroundDrawList();
    const float x = float(split_column());
    draw->AddLine(ImVec2(x, 0.0f), ImVec2(x, float(height_)), IM_COL32(255, 255, 255, 160));
    draw->AddText(ImVec2(6.0f, 4.0f), IM_COL32(255, 255, 255, 220), a_->live.id().c_str());
    draw->AddText(ImVec2(x + 6.0f, 4.0f), IM_COL32(255, 255, 255, 220), b_->live.id().c_str());
  }
}

void Viewer::panel_scene() {
  ImGui::Text("%s: %zu triangles, %u objects", scene_spec_.c_str(), scene_->triangle_count(), scene_->object_count);
  if (ImGui::BeginCombo("library", scene_schema(scene_input_) ? scene_input_.c_str() : "(file)")) {
    for (const auto& s : scene_library()) {
      if (ImGui::Selectable(s.id.c_str(), s.id == scene_input_)) {
        scene_input_ = s.id;
        scene_wanted_.clear();
        scene_message_ = open_scene(scene_input_, scene_wanted_);
        if (scene_message_.empty()) camera_message_ = apply_camera_preset(preset_spec());
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", s.description.c_str());
    }
    ImGui::EndCombo();
  }
  ImGui::InputText("file or id", &scene_input_);
  ImGui::SameLine();
  bool reload = ImGui::Button("Load");
  if (const ParamSchema* schema = scene_schema(scene_input_)) reload |= edit_params("scene", *schema, scene_wanted_);
  if (reload) {
    scene_message_ = open_scene(scene_input_, scene_wanted_);
    if (scene_message_.empty()) camera_message_ = apply_camera_preset(preset_spec());
  }
  if (!scene_message_.empty()) wrapped_colored(kRed, scene_message_);
  ImGui::ColorEdit3("background", &background_.r, ImGuiColorEditFlags_Float);
  // Both techniques alike, as `bench --scene-rect` (the reference never).
  bool scene_rect = a_->live.scene_rect();
  if (ImGui::Checkbox("scene rectangle", &scene_rect)) {
    a_->live.set_scene_rect(scene_rect);
    b_->live.set_scene_rect(scene_rect);
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("confine the techniques to the scene's projected bounding rectangle (--scene-rect on)");
}

void Viewer::panel_camera() {
  const char* kinds[] = {"scene default", "random viewpoint", "max_list"};
  bool changed = ImGui::Combo("preset", &preset_kind_, kinds, 3);
  if (preset_kind_ != 0) {
    changed |= ImGui::SliderInt("set size N", &preset_count_, 1, 64);
    changed |= ImGui::SliderInt("seed", &preset_seed_, 1, 1000);
    if (preset_kind_ == 1) changed |= ImGui::SliderInt("view I", &preset_index_, 0, std::max(preset_count_ - 1, 0));
  }
  if (changed) camera_message_ = apply_camera_preset(preset_spec());
  if (ImGui::Button("Reset to preset")) orbit_.reset();
  ImGui::SameLine();
  ImGui::TextColored(kGrey, "%s%s", preset_spec().c_str(), orbit_.moved() ? " (moved)" : "");
  ImGui::TextColored(kGrey, "drag: orbit, right/shift-drag: pan, wheel: zoom");
  if (!camera_message_.empty()) wrapped_colored(kRed, camera_message_);
}

void Viewer::panel_technique(Slot& slot, const char* label) {
  ImGui::PushID(label);
  bool changed = false;
  if (ImGui::BeginCombo("technique", slot.wanted_id.c_str())) {
    for (const auto& t : registry_.all()) {
      if (ImGui::Selectable(t.id.c_str(), t.id == slot.wanted_id)) {
        slot.wanted_id = t.id;
        slot.wanted_params.clear();
        changed = true;
      }
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("%s (%s)\n%s", t.display_name.c_str(),
                          to_string(t.exactness), t.paper.c_str());
    }
    ImGui::EndCombo();
  }
  const TechniqueDescriptor& descriptor = registry_.get(slot.wanted_id);
  changed |= edit_params(label, descriptor.params, slot.wanted_params);
  if (ImGui::Button("Defaults")) {
    slot.wanted_params.clear();
    changed = true;
  }
  if (changed) configure(slot);
  if (!slot.message.empty()) wrapped_colored(kRed, "refused: " + slot.message);
  if (!slot.render_error.empty()) wrapped_colored(kRed, "render failed: " + slot.render_error);
  if (slot.live.ready())
    wrapped_colored(kGrey, "running: " + slot.live.id() + " " + slot.live.canonical_params());
  ImGui::PopID();
}

void Viewer::panel_timings(const Slot& slot, const char* label) {
  ImGui::PushID(label);
  const int timed = slot.live.timed_frames();
  ImGui::TextWrapped("%s: %s, %s clock, ms over %s %d timed frame%s (%d warm-up frame%s left out)", label,
                     slot.live.id().c_str(), slot.live.clock_kind() == ClockKind::gl ? "gl" : "wall+glFinish",
                     timed == LiveTechnique::kWindow ? "the last" : "the", timed, timed == 1 ? "" : "s",
                     LiveTechnique::kWarmup, LiveTechnique::kWarmup == 1 ? "" : "s");
  if (timed == 0) ImGui::TextColored(kGrey, "no timed frame yet");
  if (ImGui::BeginTable("stages", 4, ImGuiTableFlags_Borders | ImGuiTableFlags_SizingStretchSame)) {
    ImGui::TableSetupColumn("stage");
    ImGui::TableSetupColumn("median");
    ImGui::TableSetupColumn("p05");
    ImGui::TableSetupColumn("p95");
    ImGui::TableHeadersRow();
    for (const auto& t : slot.live.timings()) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(t.stage.c_str());
      ImGui::TableNextColumn();
      ImGui::Text("%.2f", t.summary.median);
      ImGui::TableNextColumn();
      ImGui::Text("%.2f", t.summary.p05);
      ImGui::TableNextColumn();
      ImGui::Text("%.2f", t.summary.p95);
    }
    ImGui::EndTable();
  }
  const TechniqueCounters c = slot.live.counters();
  const uint64_t target_bytes = uint64_t(width_) * uint64_t(height_) * 16;
  ImGui::Text("memory: technique %s, scene %s, image %s", mib(c.bytes_allocated).c_str(),
              mib(scene_gpu_->bytes()).c_str(), mib(target_bytes).c_str());
  ImGui::Text("fragments %llu, dropped %llu", static_cast<unsigned long long>(c.fragments_stored),
              static_cast<unsigned long long>(c.fragments_dropped));
  ImGui::Text("passes %llu, overflow retries %llu", static_cast<unsigned long long>(c.passes),
              static_cast<unsigned long long>(c.overflow_retries));
  for (const Figure& f : c.extra) ImGui::Text("%s %.4g", f.name.c_str(), f.value);
  // What the adaptive paths avoided (the CSV's work_saved).
  for (const Figure& f : c.work_saved) ImGui::Text("saved: %s %.4g", f.name.c_str(), f.value);
  if (slot.live.scene_rect())
    ImGui::Text("saved: %s %llu", kPixelsOutsideSceneRect,
                static_cast<unsigned long long>(slot.live.pixels_outside_scene_rect()));
  ImGui::Separator();
  ImGui::PopID();
}

void Viewer::panel_diagnostics() {
  int display = int(display_);
  ImGui::RadioButton("image", &display, int(Display::image));
  ImGui::SameLine();
  ImGui::RadioButton("reference", &display, int(Display::reference));
  ImGui::SameLine();
  ImGui::RadioButton("error", &display, int(Display::error));
  ImGui::SameLine();
  ImGui::RadioButton("list length", &display, int(Display::list_length));
  ImGui::SameLine();
  ImGui::RadioButton("diagnostic", &display, int(Display::diagnostic));
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("diagnostic images the shown technique offers (if any)");
  display_ = Display(display);
  if (display_ == Display::image) return;
  if (display_ == Display::reference) ImGui::TextColored(kGrey, "exact reference (%s)", registry_.reference().id.c_str());
  if (display_ == Display::list_length) {
    colour_bar(scale_, "fragments per pixel (linear 0 .. " + std::to_string(complexity_.max) + ")");
    ImGui::Text("Psi %.4f   mean %.3f   max %u", complexity_.psi, complexity_.mean, complexity_.max);
    ImGui::Text("fragments %llu, covered pixels %llu", static_cast<unsigned long long>(complexity_.fragments),
                static_cast<unsigned long long>(complexity_.covered_pixels));
  }
  if (display_ == Display::diagnostic) {
    for (const std::string& name : diagnostic_names_) {
      const bool current = halves_[0].field && halves_[0].field->name == name;
      if (ImGui::RadioButton(name.c_str(), current)) diagnostic_name_ = name;
    }
  }
  const bool split = split_diagnostics();
  if (split) ImGui::TextColored(kGrey, "split: A left of the line, B right of it, one colour scale");
  if (display_ == Display::error)
    colour_bar(scale_, "largest abs channel error, log scale (<= 1e-4 and exact 0: the bottom colour)");
  if (display_ == Display::diagnostic && (halves_[0].field || halves_[1].field))
    colour_bar(scale_, "field value, linear (black: no fragment)");
  const Slot* slots[2] = {&shown_slot(), split ? b_.get() : nullptr};
  for (int h = 0; h < 2; ++h) {
    if (!slots[h]) continue;
    const DiagnosticHalf& half = halves_[h];
    const std::string who = (split ? std::string(h == 0 ? "A " : "B ") : std::string()) + slots[h]->live.id();
    if (display_ == Display::error && half.error) {
      const ImageError& e = *half.error;
      ImGui::Text("%s vs reference", who.c_str());
      ImGui::Text("max abs %.4g   rmse %.4g", e.max_abs, e.rmse);
      ImGui::Text("psnr %.2f dB   ssim %.4f   FLIP %.4f", e.psnr_db, e.ssim, e.flip);
      ImGui::Text("pixels off by > 1/255: %.2f%%", 100.0 * e.share_over_1_255);
    }
    if (display_ == Display::diagnostic && half.field) {
      const DiagnosticImage& d = *half.field;
      float lo = 0.0f, hi = 0.0f;
      size_t valued = 0;
      for (float v : d.values) {
        if (std::isnan(v)) continue;
        lo = valued == 0 ? v : std::min(lo, v);
        hi = valued == 0 ? v : std::max(hi, v);
        ++valued;
      }
      ImGui::TextWrapped("%s, %s: %s", who.c_str(), d.name.c_str(), d.description.c_str());
      ImGui::Text("natural range %.4g .. %.4g", d.low, d.high);
      if (valued > 0) ImGui::Text("values %.4g .. %.4g over %zu pixels", lo, hi, valued);
    }
    if (!half.message.empty()) wrapped_colored(kRed, (split ? who + ": " : std::string()) + half.message);
  }
}

void Viewer::panel_output() {
  ImGui::InputText("PNG", &screenshot_path_);
  ImGui::SameLine();
  if (ImGui::Button("Save screenshot")) screenshot_requested_ = true;
  ImGui::InputText("sweep file", &sweep_file_);
  ImGui::InputText("bench --csv", &sweep_csv_);
  if (ImGui::Button("Add this configuration to the sweep file")) add_to_sweep_file();
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("appends the equivalent `oitbench bench ...` line (A, and B when comparing)");
  if (!output_message_.empty()) ImGui::TextWrapped("%s", output_message_.c_str());
}

}  // namespace oit
