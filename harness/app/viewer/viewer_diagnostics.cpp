// The viewer's non-image displays: the exact reference, the error heatmap,
// the list-length heatmap and the technique's diagnostic fields, computed
// with the harness's own functions whenever what they depend on changes.
// In split mode the error and diagnostic displays are split like the image:
// technique A's heatmap left of the split line, B's right of it.
#include <algorithm>
#include <sstream>

#include "harness/app/viewer/viewer.h"
#include "harness/output/heatmap.h"
#include "harness/gl/check.h"

namespace oit {

int Viewer::split_column() const { return std::clamp(int(split_ * float(width_) + 0.5f), 0, width_); }

bool Viewer::split_diagnostics() const {
  return compare_ && show_ == Show::split && (display_ == Display::error || display_ == Display::diagnostic);
}

std::string Viewer::diagnostic_key() const {
  // Everything the displays depend on; a technique's image is deterministic
  // for a fixed configuration and camera.
  std::ostringstream key;
  key << int(display_) << "|" << diagnostic_name_ << "|" << scene_generation_ << "|" << background_.r << ","
      << background_.g << "," << background_.b << "|" << shown_slot().live.id() << " "
      << shown_slot().live.canonical_params() << "|";
  if (split_diagnostics()) key << split_column() << "|" << b_->live.id() << " " << b_->live.canonical_params() << "|";
  const glm::mat4 view = orbit_.camera().view, proj = projection();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) key << view[c][r] << "," << proj[c][r] << ";";
  return key.str();
}

void Viewer::upload(const Image& image) {
  glTextureSubImage2D(display_target_->color.id(), 0, 0, 0, image.width, image.height, GL_RGBA, GL_FLOAT,
                      image.rgba.data());
}

// The reference of this very view: the registry's reference technique,
// rendered as the harness renders references.
const Image& Viewer::reference_of_view() {
  if (reference_->id().empty()) {
    if (std::string m = reference_->configure(registry_.reference().id, {}, facts(), scene_gpu_->shading(), width_,
                                          height_); !m.empty())
      throw std::runtime_error(m);
  }
  reference_->render(*scene_gpu_, orbit_.camera().view, projection(), background_);
  reference_image_ = reference_->read_image();
  return reference_image_;
}

std::vector<float> Viewer::field_of(const Slot& slot, DiagnosticHalf& half) {
  if (!slot.live.ready()) throw std::runtime_error("no technique is running");
  if (display_ == Display::error) {
    const Image image = slot.live.read_image();
    half.error = compare_images(image, reference_image_);
    return error_field(image, reference_image_);
  }
  // Display::diagnostic: the field asked for (or the technique's first);
  // B in split mode shows the field of the same name when it has one.
  std::vector<DiagnosticImage> images = slot.live.diagnostic_images();
  if (images.empty()) throw std::runtime_error(slot.live.id() + " offers no diagnostic images with these parameters");
  auto it = std::find_if(images.begin(), images.end(),
                         [&](const DiagnosticImage& d) { return d.name == diagnostic_name_; });
  if (&slot == &shown_slot()) {
    for (const DiagnosticImage& d : images) diagnostic_names_.push_back(d.name);
    if (!diagnostic_name_.empty() && it == images.end())
      throw std::runtime_error(slot.live.id() + " has no diagnostic image '" + diagnostic_name_ + "'");
  }
  if (it == images.end()) it = images.begin();
  half.field = std::move(*it);
  return half.field->values;
}

void Viewer::update_diagnostics() {
  if (display_ == Display::image) return;
  const std::string key = diagnostic_key();
  if (key == diagnostics_key_) return;
  diagnostics_key_ = key;
  halves_[0] = halves_[1] = DiagnosticHalf{};
  diagnostic_names_.clear();
  const GLfloat black[4] = {0.0f, 0.0f, 0.0f, 1.0f};
  glClearNamedFramebufferfv(display_target_->framebuffer.id(), GL_COLOR, 0, black);
  try {
    if (display_ == Display::list_length) {
      complexity_ = measure_depth_complexity(*scene_gpu_, orbit_.camera().view, projection(), width_, height_);
      scale_ = list_length_scale(complexity_);
      return upload(list_length_heatmap(complexity_));
    }
    if (display_ != Display::diagnostic) reference_of_view();
    if (display_ == Display::reference) return upload(reference_image_);
  } catch (const std::exception& e) {
    drain_gl_errors();
    halves_[0].message = e.what();
    return;
  }
  // Each half on its own: one technique's failure leaves its half black.
  // Both halves share one colour scale: errors on error_scale(), a
  // diagnostic field over the union of the halves' natural ranges.
  Image shown{width_, height_, std::vector<float>(size_t(width_) * size_t(height_) * 4, 0.0f)};
  for (size_t i = 3; i < shown.rgba.size(); i += 4) shown.rgba[i] = 1.0f;
  const int split = split_diagnostics() ? split_column() : width_;
  const Slot* slots[2] = {&shown_slot(), split_diagnostics() ? b_.get() : nullptr};
  std::vector<float> fields[2];
  for (int h = 0; h < 2; ++h) {
    if (!slots[h]) continue;
    try {
      fields[h] = field_of(*slots[h], halves_[h]);
    } catch (const std::exception& e) {
      drain_gl_errors();
      halves_[h].message = e.what();
    }
  }
  scale_ = error_scale();
  if (display_ == Display::diagnostic) {
    bool first = true;
    for (const DiagnosticHalf& half : halves_) {
      if (!half.field) continue;
      scale_ = first ? ColourScale{ColourScale::Kind::linear, half.field->low, half.field->high}
                     : ColourScale{ColourScale::Kind::linear, std::min(scale_.low, half.field->low),
                                   std::max(scale_.high, half.field->high)};
      first = false;
    }
  }
  for (int h = 0; h < 2; ++h) {
    if (fields[h].empty()) continue;
    const Image heatmap = oit::heatmap(fields[h], width_, height_, scale_);
    const int x0 = h == 0 ? 0 : split, x1 = h == 0 ? split : width_;
    for (int y = 0; y < height_; ++y)
      std::copy_n(heatmap.rgba.begin() + (size_t(y) * size_t(width_) + size_t(x0)) * 4, size_t(x1 - x0) * 4,
                  shown.rgba.begin() + (size_t(y) * size_t(width_) + size_t(x0)) * 4);
  }
  upload(shown);
}

}  // namespace oit
