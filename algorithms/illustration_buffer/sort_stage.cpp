#include "algorithms/illustration_buffer/sort_stage.h"

#include <algorithm>
#include <bit>

#include "algorithms/illustration_buffer/bindings.h"
#include "algorithms/illustration_buffer/shader_variant.h"
#include "algorithms/illustration_buffer/triangle_table.h"
#include "harness/gl/check.h"
#include "harness/gl/shader_program.h"

namespace oit::illustration_buffer {
namespace {

// The smallest sort array compiled (lists of up to 4, e.g. the torus's, with
// storage=linearized or arrays, where the dynamic sort is not offered).
constexpr uint32_t kSmallestArray = 4;

}  // namespace

SortStage::SortStage(const Settings& s, Records& records) : s_(s), records_(records) {}

SortChoice SortStage::choose(const FillResult& fill) const {
  SortChoice c;
  c.dynamic = s_.sort == SortMethod::dynamic;  // sort=auto is resolved before (resolve_parameters)
  if (s_.sort == SortMethod::static_arrays) {
    c.static_arrays = true;
    c.array = IB_STATIC_ENTRIES;
    c.truncates = fill.longest > c.array;
  } else if (!c.dynamic) {
    c.array = std::min(s_.max_per_pixel, std::max(kSmallestArray, std::bit_ceil(std::max<uint32_t>(fill.longest, 1))));
    c.truncates = fill.longest > c.array;
  }
  return c;
}

void SortStage::run(const Frame& frame, const FramePlan& plan, const FillResult& fill, const SortChoice& choice,
                    const FillStage& fill_stage, const Grid& grid) {
  auto stage = frame.clock.stage("sort");
  glUseProgram(program(plan, fill, choice));
  glBindTextureUnit(IB_FRAGMENT_UNIT, records_.fragment_view.id());
  if (plan.flat_records) glBindTextureUnit(IB_FLAT_COLORS_UNIT, frame.scene.flat_colors_view());
  if (s_.ranged()) glBindTextureUnit(IB_OFFSETS_UNIT, fill_stage.offsets_view(fill));
  if (s_.stores_triangle_vertices()) {
    prepare_triangles(frame.scene);
    glBindTextureUnit(IB_SORT_TRIANGLES_UNIT, triangles_view_.id());
  }
  grid.per_covered_pixel();
  fill_stage.check_ranges(fill);
}

GLuint SortStage::program(const FramePlan& plan, const FillResult& fill, const SortChoice& choice) {
  const Variant key{choice.array, plan.flat_records, choice.truncates, fill.arrays(), choice.static_arrays};
  auto it = programs_.find(key);
  if (it == programs_.end()) {
    ShaderVariant v;
    v.ranged = s_.ranged();
    v.arrays = fill.arrays();
    v.fetch_cursor = s_.fetches_cursors();
    v.listed = s_.ranged();
    v.flat_color = plan.flat_records;
    v.truncates = choice.truncates;
    v.dynamic_sort = choice.dynamic;
    v.static_arrays = choice.static_arrays;
    v.sort_array = choice.static_arrays ? 0 : choice.array;  // IB_STATIC_ENTRIES sizes the static arrays
    v.triangle_vertices = s_.stores_triangle_vertices();
    v.surface = s_.records_surface();
    it = programs_.emplace(key, build_compute_program("algorithms/illustration_buffer/sort.comp", v.defines())).first;
  }
  return it->second.id();
}

// Once per scene: the triangle table (neighbors=triangle_index).
void SortStage::prepare_triangles(const SceneGpu& uploaded) {
  if (uploaded.serial() == triangle_scene_) return;
  triangle_scene_ = uploaded.serial();
  const TriangleTable table = build_triangle_table(uploaded.scene(), s_.weld_vertices);
  const GLsizeiptr bytes = GLsizeiptr(table.vertices_by_stable_id.size() * sizeof(glm::uvec4));
  triangles_ = make_buffer(bytes, table.vertices_by_stable_id.data(), 0);
  triangles_view_ = bytes > 0 ? make_buffer_texture(triangles_, GL_RGBA32UI, 0, bytes) : Texture();
  gl_check("uploading the illustration_buffer triangle table");
  triangle_rows_ = table.vertices_by_stable_id.size();
  isolated_triangles_ = table.isolated_triangles;
}

}  // namespace oit::illustration_buffer
