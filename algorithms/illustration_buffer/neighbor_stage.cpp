#include "algorithms/illustration_buffer/neighbor_stage.h"

#include <algorithm>
#include <bit>

#include "algorithms/illustration_buffer/shader_variant.h"
#include "harness/gl/shader_program.h"

namespace oit::illustration_buffer {
namespace {

constexpr uint32_t kLargestSearchGroup = 4;  // NeighborStage::triangle_search

}  // namespace

NeighborStage::NeighborStage(const Settings& s) : s_(s) {
  if (!s_.diffused() || !s_.heuristic()) return;  // triangle_index: triangle_search, per frame
  ShaderVariant v;
  v.merge = s_.neighbors == NeighborSearch::heuristic_merge;
  heuristic_ = build_compute_program("algorithms/illustration_buffer/neighbors.comp", v.defines());
}

void NeighborStage::prepare(const SceneGpu& uploaded, FrameParams& params) {
  if (s_.heuristic() && uploaded.serial() != scene_) {
    scene_ = uploaded.serial();
    const float radius = uploaded.scene().bounds().radius;
    inverse_radius_ = radius > 0.0f ? 1.0f / radius : 1.0f;
  }
  params.values.inverse_radius = inverse_radius_;
}

void NeighborStage::run(const Frame& frame, uint32_t longest, const Grid& grid) {
  auto stage = frame.clock.stage("neighbors");
  if (s_.heuristic()) return grid.per_fragment(heuristic_.id());
  glUseProgram(triangle_search(longest));
  grid.per_covered_pixel();
}

// neighbors=triangle_index takes a pixel's fragments IB_GROUP at a time:
// 4, or the frame's longest kept list rounded up to a power of two where
// that is shorter (llvmpipe runs the tests of fragments no list has).
GLuint NeighborStage::triangle_search(uint32_t longest) {
  const uint32_t kept = std::max<uint32_t>(std::min(longest, s_.max_per_pixel), 1);
  const uint32_t group = std::min(kLargestSearchGroup, std::bit_ceil(kept));
  auto it = triangle_searches_.find(group);
  if (it == triangle_searches_.end()) {
    ShaderVariant v;
    v.listed = s_.ranged();
    v.group = group;
    it = triangle_searches_
             .emplace(group, build_compute_program("algorithms/illustration_buffer/neighbors_triangle_index.comp",
                                                   v.defines()))
             .first;
  }
  return it->second.id();
}

}  // namespace oit::illustration_buffer
