#pragma once
// dual_depth_peeling with tie_break=triangle_id (by_triangle_id.cpp):
// composites in the reference's order (view depth, stable triangle id),
// whatever the submission order.
#include <memory>

#include "harness/toolkit/technique.h"

namespace oit {

std::unique_ptr<Technique> make_dual_depth_peeling_by_triangle_id(int max_passes, bool early_exit);

// Largest stable triangle id the tie_break=triangle_id shaders can rank
// (two bands of positive normal float bits, see by_id_shared.glsl).
constexpr uint32_t kDualDepthPeelingMaxTriangleId = 0x3f7fffffu;

}  // namespace oit
