#pragma once
// Automatic screen tiling: when a technique's storage for a frame would
// exceed the device's largest storage block or the memory budget, the
// harness renders the frame as N tiles. Each tile is a frame of its own for
// the technique: a smaller width x height and a sub-frustum projection that
// maps exactly that window of the image onto it, so a technique needs no
// code for tiling and allocates storage for one tile only. Every tile runs
// the technique's whole pass sequence; its inner rectangle is copied into
// the one target. Techniques that read neighbouring pixels declare a halo
// (TechniqueDescriptor::tile_halo): each tile is rendered with that margin
// of the image around it, so the pixels it keeps see everything they depend
// on. The frame itself, tiled or not, is rendered here too (render_frame):
// the one frame path of a bench run, the reference and the viewer. Nothing
// here knows any technique.
#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "harness/run/complexity.h"
#include "harness/toolkit/scene_rect.h"
#include "harness/toolkit/technique.h"
#include "harness/gl/handles.h"

namespace oit {

// What bounds a frame's storage on this device.
struct DeviceLimits {
  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE, or 4 x GL_MAX_TEXTURE_BUFFER_SIZE
  // (texels) when smaller
  uint64_t largest_buffer = 0;
  uint64_t memory_budget = 0;   // all of a technique's storage together
  std::string budget_source;    // how memory_budget was chosen, for `list`
};

// The current context's limits. `budget` (bytes) overrides the default
// budget: 3/4 of the free video memory where the driver reports it
// (GL_NVX_gpu_memory_info, GL_ATI_meminfo), otherwise half of the host's
// physical memory (a software rasterizer's buffers live there).
DeviceLimits query_device_limits(std::optional<uint64_t> budget = std::nullopt);

// "512M", "2G", "1.5GiB", "1000000" (bytes) -> bytes. Throws naming the
// value when it is not a positive size.
uint64_t parse_memory_size(const std::string& text);
std::string format_bytes(uint64_t bytes);

struct TilePlan {
  int width = 0, height = 0;            // the whole image
  int tile_width = 0, tile_height = 0;  // inner tiles (the last row/column may be smaller)
  int halo = 0;
  std::vector<ScreenRect> tiles;        // inner rectangles, row by row from the bottom
  StorageNeed need;                     // the largest tile's (the untiled frame's when 1 tile)

  bool tiled() const { return tiles.size() > 1; }
  int count() const { return int(tiles.size()); }
  // The technique's frame: an inner tile with its halo, or the whole image.
  int frame_width() const;
  int frame_height() const;
  // Where the technique's frame for `tile` lies in the image: the tile
  // widened by the halo, moved (not cut) to stay inside the image, so that
  // every pixel of it is a pixel of the image.
  ScreenRect window(const ScreenRect& tile) const;
};

// One tile, the whole width x height image (the technique's frame is the image).
TilePlan untiled_plan(int width, int height, int halo = 0);

// The fewest tiles (splitting the longer tile side in two each step) whose
// storage fits `limits`, from the frame's per-pixel fragment counts. One
// tile when `need` is empty or the whole frame fits. Throws naming the need
// and the limit when even 8x8-pixel tiles do not fit.
TilePlan plan_tiles(const std::function<StorageNeed(const FrameContent&)>& need, int halo,
                    const DepthComplexity& complexity, const DeviceLimits& limits);

// The projection that maps `window` of a width x height image onto a whole
// viewport: `projection` followed by a scale and offset in clip space.
glm::mat4 window_projection(const glm::mat4& projection, const ScreenRect& window, int width, int height);

// Combines the counters of the tiles of one frame (Figure::combine; bytes
// and retries are the technique's, so the largest).
TechniqueCounters combine_tile_counters(const std::vector<TechniqueCounters>& tiles);

// Diagnostic images of the tiles of one frame pasted into one image.
std::vector<DiagnosticImage> combine_tile_diagnostics(const std::vector<std::vector<DiagnosticImage>>& tiles,
                                                      const TilePlan& plan);

// Default GL state every technique may assume at the start of a frame.
void reset_gl_state();
// reset_gl_state(), then `framebuffer` cleared to the background (alpha 0);
// with `rect`, the scissor confines everything after to it.
void begin_target(GLuint framebuffer, const glm::vec3& background, const ScreenRect* rect);

// The RGBA32F image a technique composes into (Frame::target_framebuffer).
struct RenderTarget {
  Texture color;
  Framebuffer framebuffer;
  RenderTarget(int width, int height);  // throws GlError when incomplete
};

// The tile target of a technique rendered at one size in tiles: the plan
// and an RGBA32F target of one tile's window. The technique must have been
// resized to plan.frame_width() x plan.frame_height().
class Tiling {
 public:
  explicit Tiling(TilePlan plan);
  const TilePlan& plan() const { return plan_; }
  GLuint framebuffer() const { return target_ ? target_->framebuffer.id() : 0; }

 private:
  TilePlan plan_;
  std::unique_ptr<RenderTarget> target_;  // only when tiled
};

// One frame exactly as Harness::run renders it: default GL state, the whole
// target cleared to the background (alpha 0), then, with `scene_rect`, the
// scissor test enabled on the scene's projected rectangle (scene_rect.h)
// while the technique renders inside the `total` stage. Scissoring limits
// draws, glClear*/glClearNamedFramebuffer* and blits, not compute
// dispatches, glClearTexImage or buffer clears; no fragment falls outside
// the rectangle, so the image is the same. Shared with the interactive
// viewer so that it has no rendering path of its own. `record` = false: a
// warm-up frame. Returns the rectangle the technique was confined to (the
// full image without `scene_rect`).
// With a tiled `tiling`, each tile is a frame of its own for the technique
// (the tile's window and projection, Frame::tile_index), rendered into the
// tile target and its inner rectangle copied into the frame's target;
// tiles outside the scene rectangle are skipped; `total` covers every tile.
// `after_tile(i)` runs after tile i (after the whole frame untiled), for
// reading counters tile by tile in a frame that is not recorded.
ScreenRect render_frame(Technique& technique, const Frame& frame, bool record, bool scene_rect = true,
                        const Tiling* tiling = nullptr, const std::function<void(int)>& after_tile = {});
// The scene's projected rectangle for this frame's camera and size.
ScreenRect scene_rect_of(const Frame& frame);

}  // namespace oit
