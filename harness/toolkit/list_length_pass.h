#pragma once
// A cheap counting pass for techniques that size per-pixel storage from the
// view they are about to render (k=auto): one geometry pass with no depth
// test counts every pixel's fragments; the longest list of the frame sizes
// the storage. Technique-independent; the technique times it (stage `count`).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "base/params.h"
#include "harness/toolkit/technique.h"
#include "harness/gl/handles.h"

namespace oit {

class ListLengthPass {
 public:
  ListLengthPass();
  // The per-pixel count target for this size.
  void resize(int width, int height);
  // Draws frame.scene with the frame's camera into counts() and does not
  // wait for it: for a caller that reduces the counts on the device.
  // Leaves another framebuffer and program bound.
  void draw(const Frame& frame);
  // draw(), then read_back(): the longest per-pixel fragment list (0 for
  // an empty view); it waits for the pass: the caller needs the number
  // before going on.
  uint32_t longest_list(const Frame& frame);
  // Reads the last draw's counts back (host_counts, total_fragments) and
  // returns the longest list.
  uint32_t read_back();
  // The fragments the last read-back counted, summed from it (exact: every
  // count is a whole number below 2^24).
  uint64_t total_fragments() const { return total_; }
  // The counts the last read-back read, pixel i = x + y * width (rows from the
  // bottom), whole numbers in float.
  const std::vector<float>& host_counts() const { return readback_; }
  // The R32F count target (4 bytes per pixel).
  uint64_t bytes_allocated() const;
  // That target, holding the last pass's per-pixel counts (e.g. for a prefix sum).
  const Texture& counts() const { return counts_; }

 private:
  Program program_;
  Texture counts_;
  Framebuffer framebuffer_;
  std::vector<float> readback_;
  int width_ = 0, height_ = 0;
  uint64_t total_ = 0;
};

// The ranges of a linearized buffer from the counts a ListLengthPass read
// back (host_counts): pixel i owns [offsets[i], offsets[i + 1]) of an array
// holding min(count, most_per_pixel) fragments of every pixel; pixels + 1
// values, the last one the total. Throws when the total passes 32 bits.
void offsets_from_counts(const std::vector<float>& counts, std::vector<uint32_t>& offsets,
                         uint32_t most_per_pixel = UINT32_MAX);
// The same from counts held as uints (a fill's final cursors, SlotCursors::read_back).
void offsets_from_counts(const std::vector<uint32_t>& counts, std::vector<uint32_t>& offsets,
                         uint32_t most_per_pixel = UINT32_MAX);
// How the fill of such ranges takes a fragment's slot in its pixel's range
// (the parameter `fill` of every technique that fills them): an image
// atomic on the pixel's cursor, or the cursor as the pixel's R32UI colour,
// read and incremented in primitive order through framebuffer fetch
// (GL_EXT_shader_framebuffer_fetch, no atomic); auto: framebuffer fetch
// where the device has it, resolved before the technique exists
// (resolve_slot_fill, in the technique's resolution rule).
enum class SlotFill { automatic, atomic, framebuffer_fetch };
inline const Choices<SlotFill> kSlotFills{
    {SlotFill::automatic, "auto"}, {SlotFill::atomic, "atomic"}, {SlotFill::framebuffer_fetch, "framebuffer_fetch"}};
// The fill `requested` becomes on `device`: auto resolved, the others as given.
SlotFill resolve_slot_fill(SlotFill requested, const DeviceProfile& device);
// Whether a resolved `fill` takes slots by framebuffer fetch; throws
// std::logic_error for an unresolved auto.
bool fills_by_framebuffer_fetch(SlotFill fill);
// "" when `device` can run `fill`, else why not (naming fill=).
std::string missing_slot_fill_feature(SlotFill fill, const DeviceProfile& device);

// The per-pixel cursors a linearized fill takes its slots from: with
// framebuffer fetch the R32UI colour target of the fill's framebuffer, else
// a buffer the fill increments with image atomics. 4 bytes per pixel.
class SlotCursors {
 public:
  explicit SlotCursors(SlotFill fill) : fetch_(fills_by_framebuffer_fetch(fill)) {}
  bool by_framebuffer_fetch() const { return fetch_; }
  // Storage for width x height; `owner` names the technique in GL errors.
  void resize(int width, int height, const std::string& owner);
  // Every cursor := its pixel's offset (the first width x height values of
  // `offsets`, uints in pixel order).
  void start(const Buffer& offsets) const;
  // Every cursor := 0: a fill into per-pixel arrays, whose final cursors are
  // the pixels' fragment counts.
  void start_at_zero() const;
  // The framebuffer the fill draws into: the cursor target with framebuffer
  // fetch, else one without attachments.
  const Framebuffer& fill_framebuffer() const { return framebuffer_; }
  // Binds the cursor buffer to image `unit` for the fill's atomics (nothing
  // to bind with framebuffer fetch); unbind_image(unit) after the fill.
  void bind_image(GLuint unit) const;
  static void unbind_image(GLuint unit);
  // Where each pixel's fill ended, for a texelFetch after the fill: the
  // R32UI 2D target (framebuffer fetch) or an R32UI buffer texture.
  GLuint final_cursors() const { return fetch_ ? target_.id() : view_.id(); }
  // The pixels whose fill did not end at the end of their range (cursor !=
  // offsets[p + 1], `offsets` the W*H + 1 values start() was given), read
  // back on the host: a check of every pixel for passes that do not visit
  // them all (4 bytes per pixel read back).
  uint32_t count_mismatched(const std::vector<uint32_t>& offsets) const;
  // Every pixel's final cursor, read back on the host (pixel i = x + y * width).
  const std::vector<uint32_t>& read_back() const;

 private:
  bool fetch_;
  int width_ = 0, height_ = 0;
  mutable std::vector<uint32_t> ends_;  // count_mismatched's read-back
  Buffer buffer_;
  Texture view_, target_;
  Framebuffer framebuffer_;
};

// Throws std::runtime_error when the pixels a linearized buffer's range
// check counted (`mismatched`: the fill ended elsewhere than at the end of
// the counted range) are not 0: the records, and the image, would be wrong.
void fail_on_mismatched_ranges(const std::string& technique, uint32_t mismatched, uint64_t counted_fragments);

// min(count, most_per_pixel) of every pixel, as uints.
void lengths_from_counts(const std::vector<float>& counts, std::vector<uint32_t>& lengths,
                         uint32_t most_per_pixel = UINT32_MAX);
void lengths_from_counts(const std::vector<uint32_t>& counts, std::vector<uint32_t>& lengths,
                         uint32_t most_per_pixel = UINT32_MAX);

// Throws std::runtime_error when a technique's largest buffer of per-pixel
// slots, `largest_buffer_bytes` for k slots per pixel at width x height,
// exceeds the device's largest storage block: "<technique>: k=<k> at
// <width>x<height> needs <N> MiB for <buffer>, more than the device's
// largest storage block (<M> MiB); lower k or the size".
void check_slots_fit(const std::string& technique, int k, int width, int height, uint64_t largest_buffer_bytes,
                     const std::string& buffer);

// The most slots per pixel (at least 1, at most max_slots) that a technique
// sizing itself from ListLengthPass may allocate at width x height: all its
// per-slot arrays (bytes_per_slot in all) within memory_cap_bytes, and its
// largest single array (largest_array_bytes_per_slot) within the device's
// largest storage block.
int slots_per_pixel_cap(int width, int height, uint64_t memory_cap_bytes, uint64_t bytes_per_slot,
                        uint64_t largest_array_bytes_per_slot, int max_slots);

// The slots per pixel of a k-buffer (kbuffer, bucketed_kbuffer), from its
// parameters `k` (an integer or auto) and `auto_k_memory_mb`: the fixed k,
// or with k=auto the view's depth complexity, counted every frame by a
// ListLengthPass (stage "count") and capped by slots_per_pixel_cap.
class SlotsPerPixel {
 public:
  SlotsPerPixel(const ParamSet& params, int max_k);
  bool automatic() const { return count_pass_.has_value(); }
  int fixed() const { return fixed_; }  // 0 with k=auto
  // k=auto: the counting target and the cap for width x height, from the
  // bytes of all per-slot arrays and of the largest one (slots_per_pixel_cap).
  void resize(int width, int height, uint64_t bytes_per_slot, uint64_t largest_array_bytes_per_slot);
  // This frame's k: the fixed one, or counted (a stage of its own) and capped.
  int for_frame(const Frame& frame);
  // The counting target's bytes and geometry passes (none with a fixed k).
  uint64_t bytes_allocated() const { return automatic() ? count_pass_->bytes_allocated() : 0; }
  uint64_t passes() const { return automatic() ? 1 : 0; }
  // Appends k_used and, with k=auto, longest_list, k_cap and k_capped (1:
  // the view needed more slots than the cap allows, so the fragments beyond
  // k_used were handled as with a fixed k).
  void add_figures(std::vector<Figure>& extra, int k_used) const;

 private:
  int max_k_, fixed_;
  uint64_t memory_cap_bytes_;
  std::optional<ListLengthPass> count_pass_;
  int cap_;
  uint32_t longest_list_ = 0;
};

}  // namespace oit
