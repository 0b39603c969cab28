#include "harness/run/tiling.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cmath>
#include <map>
#include <stdexcept>

#include "harness/gl/check.h"
#include "harness/gl/gl.h"

namespace oit {

namespace {

// GL_NVX_gpu_memory_info and GL_ATI_meminfo (values in KiB).
constexpr GLenum kNvxAvailableVideoMemory = 0x9049;
constexpr GLenum kAtiTextureFreeMemory = 0x87FC;
constexpr int kSmallestTile = 8;

bool has_extension(const char* name) {
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i) {
    const auto* extension = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)));
    if (extension && std::string(extension) == name) return true;
  }
  return false;
}

std::pair<uint64_t, std::string> default_budget() {
  if (has_extension("GL_NVX_gpu_memory_info")) {
    GLint kib = 0;
    glGetIntegerv(kNvxAvailableVideoMemory, &kib);
    if (kib > 0) return {uint64_t(kib) * 1024 / 4 * 3, "3/4 of the free video memory (GL_NVX_gpu_memory_info)"};
  }
  if (has_extension("GL_ATI_meminfo")) {
    GLint kib[4] = {};
    glGetIntegerv(kAtiTextureFreeMemory, kib);
    if (kib[0] > 0) return {uint64_t(kib[0]) * 1024 / 4 * 3, "3/4 of the free video memory (GL_ATI_meminfo)"};
  }
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  const uint64_t host = pages > 0 && page > 0 ? uint64_t(pages) * uint64_t(page) : uint64_t(8) << 30;
  return {host / 2, "half the host's physical memory (no video-memory query)"};
}

// Fragments and longest list of the pixels of `rect`.
FrameContent content_of(const DepthComplexity& complexity, const ScreenRect& rect) {
  FrameContent content{rect.width, rect.height, 0, 0};
  for (int y = rect.y; y < rect.y + rect.height; ++y) {
    const uint32_t* row = complexity.per_pixel.data() + size_t(y) * size_t(complexity.width);
    for (int x = rect.x; x < rect.x + rect.width; ++x) {
      content.fragments += row[x];
      content.longest_list = std::max(content.longest_list, row[x]);
    }
  }
  return content;
}

bool fits(const StorageNeed& need, const DeviceLimits& limits) {
  return need.largest_buffer <= limits.largest_buffer && need.total <= limits.memory_budget;
}

std::vector<ScreenRect> grid(int width, int height, int tile_width, int tile_height) {
  std::vector<ScreenRect> tiles;
  for (int y = 0; y < height; y += tile_height)
    for (int x = 0; x < width; x += tile_width)
      tiles.push_back({x, y, std::min(tile_width, width - x), std::min(tile_height, height - y)});
  return tiles;
}

}  // namespace

DeviceLimits query_device_limits(std::optional<uint64_t> budget) {
  DeviceLimits limits;
  GLint64 block = 0, texels = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &block);
  glGetInteger64v(GL_MAX_TEXTURE_BUFFER_SIZE, &texels);
  limits.largest_buffer = block > 0 ? uint64_t(block) : uint64_t(128) << 20;
  // Techniques also read their buffers through buffer textures, whose limit
  // counts texels of at least 4 bytes (R32UI views).
  if (texels > 0) limits.largest_buffer = std::min(limits.largest_buffer, uint64_t(texels) * 4);
  if (budget) {
    limits.memory_budget = *budget;
    limits.budget_source = "--memory-budget";
  } else {
    std::tie(limits.memory_budget, limits.budget_source) = default_budget();
  }
  return limits;
}

uint64_t parse_memory_size(const std::string& text) {
  static const std::map<std::string, double> units = {
      {"", 1.0},         {"b", 1.0},          {"k", 1024.0},       {"kb", 1024.0},     {"kib", 1024.0},
      {"m", 1048576.0},  {"mb", 1048576.0},   {"mib", 1048576.0},  {"g", 1073741824.0}, {"gb", 1073741824.0},
      {"gib", 1073741824.0}, {"t", 1099511627776.0}, {"tb", 1099511627776.0}, {"tib", 1099511627776.0}};
  char* end = nullptr;
  errno = 0;
  const double number = std::strtod(text.c_str(), &end);
  const bool overflow = errno == ERANGE && number > 1.0;  // 1e400: HUGE_VAL
  const size_t used = size_t(end - text.c_str());
  std::string unit = text.substr(used);
  std::transform(unit.begin(), unit.end(), unit.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  const auto scale = units.find(unit);
  if (used != 0 && scale != units.end() && (overflow || (std::isfinite(number) && number * scale->second > 1.8e19)))
    throw std::invalid_argument("memory size '" + text + "' is too large: at most 16E (2^64 bytes)");
  if (used == 0 || scale == units.end() || !std::isfinite(number) || number * scale->second < 1.0) {
    throw std::invalid_argument("memory size '" + text + "' is not a positive size such as 512M, 2G or 1.5GiB");
  }
  return uint64_t(number * scale->second);
}

std::string format_bytes(uint64_t bytes) {
  char text[32];
  if (bytes >= (uint64_t(1) << 30)) std::snprintf(text, sizeof text, "%.1f GiB", double(bytes) / double(1 << 30));
  else if (bytes >= (uint64_t(1) << 20)) std::snprintf(text, sizeof text, "%.0f MiB", double(bytes) / double(1 << 20));
  else if (bytes >= 1024) std::snprintf(text, sizeof text, "%.0f KiB", double(bytes) / 1024.0);
  else std::snprintf(text, sizeof text, "%llu bytes", static_cast<unsigned long long>(bytes));
  return text;
}

int TilePlan::frame_width() const { return tiled() ? std::min(width, tile_width + 2 * halo) : width; }
int TilePlan::frame_height() const { return tiled() ? std::min(height, tile_height + 2 * halo) : height; }

ScreenRect TilePlan::window(const ScreenRect& tile) const {
  if (!tiled()) return {0, 0, width, height};
  const int w = frame_width(), h = frame_height();
  return {std::clamp(tile.x - halo, 0, width - w), std::clamp(tile.y - halo, 0, height - h), w, h};
}

TilePlan untiled_plan(int width, int height, int halo) {
  TilePlan plan;
  plan.width = width;
  plan.height = height;
  plan.halo = std::max(halo, 0);
  plan.tile_width = width;
  plan.tile_height = height;
  plan.tiles = {{0, 0, width, height}};
  return plan;
}

TilePlan plan_tiles(const std::function<StorageNeed(const FrameContent&)>& need, int halo,
                    const DepthComplexity& complexity, const DeviceLimits& limits) {
  TilePlan plan = untiled_plan(complexity.width, complexity.height, halo);
  if (!need) return plan;
  for (;;) {
    // Every tile's storage is sized for its window (tile and halo); the
    // technique is resized once, for the largest.
    StorageNeed largest;
    bool all_fit = true;
    for (const ScreenRect& tile : plan.tiles) {
      const StorageNeed n = need(content_of(complexity, plan.window(tile)));
      largest.largest_buffer = std::max(largest.largest_buffer, n.largest_buffer);
      largest.total = std::max(largest.total, n.total);
      all_fit = all_fit && fits(n, limits);
    }
    plan.need = largest;
    if (all_fit) return plan;
    if (plan.tile_width <= kSmallestTile && plan.tile_height <= kSmallestTile) {
      throw std::runtime_error("even " + std::to_string(kSmallestTile) + "x" + std::to_string(kSmallestTile) +
                               "-pixel tiles need " + format_bytes(largest.largest_buffer) + " in one buffer and " +
                               format_bytes(largest.total) + " in all; the device allows " +
                               format_bytes(limits.largest_buffer) + " per buffer and a budget of " +
                               format_bytes(limits.memory_budget) + " (" + limits.budget_source + ")");
    }
    if (plan.tile_width >= plan.tile_height) plan.tile_width = (plan.tile_width + 1) / 2;
    else plan.tile_height = (plan.tile_height + 1) / 2;
    plan.tiles = grid(plan.width, plan.height, plan.tile_width, plan.tile_height);
  }
}

glm::mat4 window_projection(const glm::mat4& projection, const ScreenRect& window, int width, int height) {
  // Window x in [window.x, window.x + window.width) of the image becomes
  // NDC [-1, 1]: ndc' = ndc * W / w + (W - 2 x - w) / w, applied to clip
  // coordinates as x' = s x + t w_clip.
  glm::mat4 to_window(1.0f);
  to_window[0][0] = float(width) / float(window.width);
  to_window[1][1] = float(height) / float(window.height);
  to_window[3][0] = float(width - 2 * window.x - window.width) / float(window.width);
  to_window[3][1] = float(height - 2 * window.y - window.height) / float(window.height);
  return to_window * projection;
}

TechniqueCounters combine_tile_counters(const std::vector<TechniqueCounters>& tiles) {
  TechniqueCounters all;
  if (tiles.empty()) return all;
  double weight_total = 0.0;
  for (const TechniqueCounters& t : tiles) weight_total += double(t.fragments_stored);
  auto merge = [&](std::vector<Figure>& into, const Figure& f, double weight) {
    auto it = std::find_if(into.begin(), into.end(), [&](const Figure& g) { return g.name == f.name; });
    if (it == into.end()) it = into.insert(into.end(), {f.name, f.combine == Combine::max ? f.value : 0.0, f.combine});
    switch (f.combine) {
      case Combine::sum: it->value += f.value; break;
      case Combine::max: it->value = std::max(it->value, f.value); break;
      case Combine::mean: it->value += f.value * weight; break;
    }
  };
  for (const TechniqueCounters& t : tiles) {
    all.bytes_allocated = std::max(all.bytes_allocated, t.bytes_allocated);
    all.overflow_retries = std::max(all.overflow_retries, t.overflow_retries);
    all.fragments_stored += t.fragments_stored;
    all.fragments_dropped += t.fragments_dropped;
    all.passes += t.passes;
    const double weight = weight_total > 0.0 ? double(t.fragments_stored) / weight_total : 1.0 / double(tiles.size());
    for (const Figure& f : t.extra) merge(all.extra, f, weight);
    for (const Figure& f : t.work_saved) merge(all.work_saved, f, weight);
  }
  return all;
}

std::vector<DiagnosticImage> combine_tile_diagnostics(const std::vector<std::vector<DiagnosticImage>>& tiles,
                                                      const TilePlan& plan) {
  if (tiles.empty()) return {};
  if (!plan.tiled()) return tiles.front();
  std::vector<DiagnosticImage> all = tiles.front();
  for (DiagnosticImage& image : all) {
    image.width = plan.width;
    image.height = plan.height;
    image.values.assign(size_t(plan.width) * size_t(plan.height), NAN);
  }
  for (size_t t = 0; t < tiles.size(); ++t) {
    const ScreenRect& tile = plan.tiles[t];
    const ScreenRect window = plan.window(tile);
    for (size_t d = 0; d < all.size() && d < tiles[t].size(); ++d) {
      const DiagnosticImage& part = tiles[t][d];
      for (int y = tile.y; y < tile.y + tile.height; ++y)
        for (int x = tile.x; x < tile.x + tile.width; ++x)
          all[d].values[size_t(y) * size_t(plan.width) + size_t(x)] =
              part.values[size_t(y - window.y) * size_t(part.width) + size_t(x - window.x)];
    }
  }
  return all;
}

void reset_gl_state() {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glUseProgram(0);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);
  glDisable(GL_STENCIL_TEST);
  glDisable(GL_SCISSOR_TEST);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

RenderTarget::RenderTarget(int width, int height) {
  color = make_texture_2d(GL_RGBA32F, width, height);
  framebuffer = make_framebuffer();
  glNamedFramebufferTexture(framebuffer.id(), GL_COLOR_ATTACHMENT0, color.id(), 0);
  if (glCheckNamedFramebufferStatus(framebuffer.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    throw GlError("RGBA32F render target of " + std::to_string(width) + "x" + std::to_string(height) +
                  " is incomplete (the device could not allocate it)");
  }
}

ScreenRect scene_rect_of(const Frame& frame) {
  return projected_scene_rect(frame.scene.bounding_box(), frame.projection * frame.view, frame.width, frame.height);
}

Tiling::Tiling(TilePlan plan) : plan_(std::move(plan)) {
  if (plan_.tiled()) target_ = std::make_unique<RenderTarget>(plan_.frame_width(), plan_.frame_height());
}

void begin_target(GLuint framebuffer, const glm::vec3& background, const ScreenRect* rect) {
  reset_gl_state();
  const GLfloat clear_color[4] = {background.r, background.g, background.b, 0.0f};
  glClearNamedFramebufferfv(framebuffer, GL_COLOR, 0, clear_color);
  if (rect) {
    glEnable(GL_SCISSOR_TEST);
    glScissor(rect->x, rect->y, rect->width, rect->height);
  }
}

namespace {

ScreenRect intersection(const ScreenRect& a, const ScreenRect& b) {
  const int x0 = std::max(a.x, b.x), y0 = std::max(a.y, b.y);
  const int x1 = std::min(a.x + a.width, b.x + b.width), y1 = std::min(a.y + a.height, b.y + b.height);
  return x1 > x0 && y1 > y0 ? ScreenRect{x0, y0, x1 - x0, y1 - y0} : ScreenRect{};
}

// Tile `index` of a tiled frame: the technique renders the tile's window as
// a frame of its own; the tile's inner rectangle is copied into the target.
// False when the tile lies outside the scene's rectangle: nothing to render.
bool render_tile(Technique& technique, const Frame& frame, const Tiling& tiling, int index, const ScreenRect* rect) {
  const TilePlan& plan = tiling.plan();
  const ScreenRect& tile = plan.tiles[size_t(index)];
  if (rect && intersection(*rect, tile).pixels() == 0) return false;
  const ScreenRect window = plan.window(tile);
  const Frame part{frame.scene,           frame.view,  window_projection(frame.projection, window, frame.width, frame.height),
                   window.width,          window.height, frame.background, tiling.framebuffer(), frame.clock, index,
                   plan.count(),          window.x,    window.y};
  ScreenRect local;
  if (rect) {
    local = intersection(*rect, window);
    local.x -= window.x;
    local.y -= window.y;
  }
  begin_target(tiling.framebuffer(), frame.background, rect ? &local : nullptr);
  frame.scene.bind();
  technique.render(part);
  reset_gl_state();
  glBlitNamedFramebuffer(tiling.framebuffer(), frame.target_framebuffer, tile.x - window.x, tile.y - window.y,
                         tile.x - window.x + tile.width, tile.y - window.y + tile.height, tile.x, tile.y,
                         tile.x + tile.width, tile.y + tile.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  return true;
}

}  // namespace

ScreenRect render_frame(Technique& technique, const Frame& frame, bool record, bool scene_rect, const Tiling* tiling,
                        const std::function<void(int)>& after_tile) {
  // Before the scissor: the pixels the scene cannot reach show the background.
  const ScreenRect rect = scene_rect ? scene_rect_of(frame) : ScreenRect{0, 0, frame.width, frame.height};
  const bool tiled = tiling && tiling->plan().tiled();
  begin_target(frame.target_framebuffer, frame.background, scene_rect && !tiled ? &rect : nullptr);
  frame.clock.begin_frame(record);
  {
    auto total = frame.clock.stage("total");
    if (!tiled) {
      frame.scene.bind();
      technique.render(frame);
      if (after_tile) after_tile(0);
    } else {
      for (int i = 0; i < tiling->plan().count(); ++i) {
        if (render_tile(technique, frame, *tiling, i, scene_rect ? &rect : nullptr) && after_tile) after_tile(i);
      }
    }
  }
  frame.clock.end_frame();
  reset_gl_state();
  return rect;
}

}  // namespace oit
