#pragma once
// What the two depth peelers (depth_peeling, dual_depth_peeling) share,
// written once: their parameters and the choice between their tie_break
// variants, the triangle-id limit of the tie_break=triangle_id variants,
// their counters and the GL blend state they leave behind.
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <memory>
#include <string>

#include "harness/toolkit/technique.h"
#include "harness/gl/pass_queries.h"

namespace oit {

// The raw bits of a float, for clearing integer key textures to a depth.
uint32_t float_bits(float value);

// What each peeler says about itself: its three parameters (the defaults
// and ranges are the same: max_passes 64 in [1, 4096], early_exit true,
// tie_break triangle_id or submission) and what its early exit saves.
struct PeelingText {
  std::string max_passes, early_exit, tie_break, early_exit_saves;
};
using PeelerFactory = std::unique_ptr<Technique> (*)(int max_passes, bool early_exit);
// The PeelerFactory of a peeler class constructed from (max_passes, early_exit).
template <class T>
std::unique_ptr<Technique> make_peeler(int max_passes, bool early_exit) {
  return std::make_unique<T>(max_passes, early_exit);
}

// `d` (the peeler's id, names, paper and quality_sweep) with what both
// peelers share filled in: params, stages (clear, peel, compose), exactness
// (exact), adaptive_switches (early_exit on and off), storage_need
// (per-pixel textures only, `bytes_per_pixel` of the larger variant: tiled
// only under a small --memory-budget) and create, which picks
// `by_triangle_id` or `by_submission` by tie_break.
TechniqueDescriptor describe_peeler(TechniqueDescriptor d, const PeelingText& text, uint64_t bytes_per_pixel,
                                    PeelerFactory by_triangle_id, PeelerFactory by_submission);

// bytes_allocated, passes and work_saved passes_avoided (geometry passes
// early exit did not run; zero without it, where all max_passes run).
TechniqueCounters peeling_counters(uint64_t bytes_allocated, uint64_t passes, int max_passes, bool early_exit);

// What a tie_break=triangle_id peeler composited: pass p's selection is
// composited by pass p + 1, so passes 2 .. passes - 1 of `selected` count;
// the rest of `all_fragments` (every fragment, counted by pass 1) was
// dropped, when the passes ran out. Read lazily in counters(), so no frame
// waits for the queries.
void count_selected_fragments(TechniqueCounters& c, const Query& all_fragments, const PassSampleQueries& selected);

// The full-screen resolve of a tie_break=triangle_id peeler: clears `state`
// to `nothing_here`, draws `resolve` into it with `draw` (the caller has
// bound its inputs) and counts the pixels that selected a fragment into
// `selected`.
void resolve_selection(const Framebuffer& state, const uint32_t nothing_here[4], const Program& resolve,
                       const Query& selected, const std::function<void()>& draw);

// Back to GL's default blending (GL_FUNC_ADD, ONE, ZERO), disabled, which
// other techniques may assume.
void restore_default_blending();

// The tie_break=triangle_id candidate keys rank stable triangle ids up to a
// limit: checks a scene against it, once per uploaded scene.
class TriangleIdLimit {
 public:
  TriangleIdLimit(std::string technique, uint32_t largest_id)
      : technique_(std::move(technique)), largest_id_(largest_id) {}
  // Throws std::runtime_error naming the technique, the scene and its id.
  void check(const SceneGpu& scene);

 private:
  std::string technique_;
  uint32_t largest_id_;
  uint64_t checked_scene_ = 0;  // SceneGpu::serial, 0: none yet
};

// The skeleton both tie_break=triangle_id peelers share: the pass cap and
// early exit, the fragment queries, the triangle-id limit, the loop's
// decision after each geometry pass, the compose stage and counters(). A
// peeler renders: begin_frame, then per pass its geometry pass and
// `continue_after`, then `compose`.
class TriangleIdPeeler : public Technique {
 public:
  TechniqueCounters counters() const override;

 protected:
  TriangleIdPeeler(std::string technique, uint32_t largest_id, int max_passes, bool early_exit,
                   uint64_t bytes_per_pixel);
  void set_size(int width, int height) {
    width_ = width;
    height_ = height;
  }
  // Checks the scene's triangle ids and starts the pass count.
  void begin_frame(const Frame& frame);
  // Counts geometry pass `pass` and says whether to go on: not after the
  // last allowed pass (what it selects is never composited, so no state is
  // needed), else after `resolve` (which writes the next state) unless it
  // selected nothing and early exit is on.
  bool continue_after(int pass, const std::function<bool()>& resolve);
  // Pass 1: `init` into `target`, blended by `reduction` (GL_MIN or GL_MAX
  // of the depths it writes), with nothing discarded and no depth test, so
  // that fragments_query_ counts every fragment; blending off afterwards.
  void draw_counting_init_pass(const Frame& frame, const Program& init, const Framebuffer& target,
                               GLenum reduction) const;
  // Whether pass `pass`'s resolve selected a fragment anywhere; waits for the
  // pass only when early exit needs to know.
  bool selected_anything(int pass) const { return !early_exit_ || selected_queries_.result(size_t(pass)) != 0; }
  // The compose stage: GL's default blending back, `inputs` bound to the
  // units from OIT_FIRST_TECHNIQUE_BINDING on, `program` drawn full-screen.
  void compose(const Frame& frame, const Program& program, std::initializer_list<const Texture*> inputs) const;

  const int max_passes_;
  const bool early_exit_;
  uint64_t passes_ = 0;
  int width_ = 0, height_ = 0;
  Query fragments_query_;              // pass 1: every fragment
  PassSampleQueries selected_queries_;  // pass p's resolve: fragments selected

 private:
  TriangleIdLimit triangle_ids_;
  uint64_t bytes_per_pixel_;
};

}  // namespace oit
