#pragma once
// The viewer's state and frame loop. The window holds the scene area (the
// rendered image at 1:1, top-left, exactly --size pixels) and a control
// panel to its right. Every image comes from registry techniques rendered
// through the harness's render_frame(); diagnostics use the harness's
// comparison, heatmap and depth-complexity functions.
#include <memory>
#include <optional>
#include <string>

#include "harness/app/viewer/live_technique.h"
#include "harness/app/viewer/orbit_camera.h"
#include "harness/app/viewer/sweep_line.h"
#include "harness/app/viewer/view_options.h"
#include "harness/output/error_metrics.h"
#include "harness/output/heatmap.h"
#include "harness/gl/glfw_window.h"

namespace oit {

class Viewer {
 public:
  static constexpr int kPanelWidth = 470;
  static constexpr int kMinHeight = 940;
  // The timings go below the scene area when that leaves at least this much.
  static constexpr int kBelowMinWidth = 360, kBelowMinHeight = 240;

  Viewer(GlfwWindowContext& window, const ViewOptions& options);
  ~Viewer();
  int run();

 private:
  enum class Display { image, reference, error, list_length, diagnostic };
  enum class Show { a, b, split };
  // Technique A or B: what the user asked for and what runs.
  struct Slot {
    explicit Slot(LiveTechnique live) : live(std::move(live)) {}
    LiveTechnique live;
    std::string wanted_id;
    RawParams wanted_params;  // edited in the panel; may be invalid
    std::string message;      // why wanted_* is not what runs ("" = it is)
    std::string render_error; // the last render threw: not rendered until reconfigured
  };

  // Scene and camera.
  std::string open_scene(const std::string& spec, const RawParams& params);
  std::string apply_camera_preset(const std::string& spec);
  std::string preset_spec() const;
  glm::mat4 projection() const;
  SceneFacts facts() const;
  // Techniques.
  void configure(Slot& slot);
  void render_slot(Slot& slot);
  // The technique the scene area and the diagnostics show: A, unless the
  // comparison is on and toggled to B (split: A left, B right).
  const Slot& shown_slot() const { return compare_ && show_ == Show::b ? *b_ : *a_; }
  int split_column() const;  // first column of B in split mode
  // What one technique's error or diagnostic heatmap says (viewer_diagnostics.cpp).
  struct DiagnosticHalf {
    std::optional<ImageError> error;
    std::optional<DiagnosticImage> field;  // the one shown (values kept for the panel's range)
    std::string message;                   // why it is black
  };
  // Error and diagnostic displays split like the image (A | B).
  bool split_diagnostics() const;
  void update_diagnostics();
  std::string diagnostic_key() const;
  const Image& reference_of_view();
  // The half's values: its error field, or its diagnostic field.
  std::vector<float> field_of(const Slot& slot, DiagnosticHalf& half);
  void upload(const Image& image);
  // Output.
  // `source` (linear RGBA32F) as the PNG writer would write it, into
  // encoder_ (RGBA8), which the window copies 1:1.
  void encode_for_display(GLuint source_texture);
  void draw_scene_area(int framebuffer_height);
  void handle_mouse();
  void save_screenshot(const std::string& path);
  void add_to_sweep_file();
  ViewConfig config_of(const Slot& slot) const;
  // The panel (viewer_panel.cpp).
  void draw_panel(int framebuffer_width, int framebuffer_height);
  void panel_scene();
  void panel_camera();
  void panel_technique(Slot& slot, const char* label);
  void panel_timings(const Slot& slot, const char* label);
  void panel_diagnostics();
  void panel_output();

  GlfwWindowContext& window_;
  const TechniqueRegistry& registry_;
  ViewOptions options_;
  int width_ = 0, height_ = 0;
  glm::vec3 background_{0.0f};

  std::string scene_spec_;       // as loaded
  RawParams scene_params_;       // as loaded
  std::string scene_input_;      // the panel's scene field
  RawParams scene_wanted_;       // the panel's scene parameters
  std::string scene_message_;
  std::unique_ptr<Scene> scene_;
  std::unique_ptr<SceneGpu> scene_gpu_;
  int scene_generation_ = 0;     // diagnostics key: bumps on every load

  int preset_kind_ = 0;          // 0 default, 1 random view, 2 max_list
  int preset_count_ = 16, preset_seed_ = 1, preset_index_ = 0;
  std::string camera_message_;
  OrbitCamera orbit_;

  std::unique_ptr<Slot> a_, b_;
  bool compare_ = false;
  Show show_ = Show::a;
  float split_ = 0.5f;           // share of the width showing A

  Display display_ = Display::image;
  std::unique_ptr<LiveTechnique> reference_;
  std::string diagnostics_key_;  // what the diagnostics below were computed for
  Image reference_image_;
  DepthComplexity complexity_;
  std::string diagnostic_name_;             // wanted diagnostic image ("": the technique's first)
  std::vector<std::string> diagnostic_names_;  // what the shown technique offers
  DiagnosticHalf halves_[2];                // the shown technique; B in split mode
  ColourScale scale_ = error_scale();       // the heatmap shown (both halves), for the panel's colour bar
  std::unique_ptr<RenderTarget> display_target_;  // uploaded diagnostic image
  struct DisplayEncoding {
    Program program;  // shaders/display_srgb.comp
    Texture texture;  // RGBA8, sRGB-encoded bytes
    Framebuffer framebuffer;
  };
  std::unique_ptr<DisplayEncoding> encoder_;

  std::string screenshot_path_ = "oitbench_view.png";
  std::string sweep_file_, sweep_csv_;
  std::string output_message_;
  bool screenshot_requested_ = false;
  bool space_was_down_ = false;
};

}  // namespace oit
