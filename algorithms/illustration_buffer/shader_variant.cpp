#include "algorithms/illustration_buffer/shader_variant.h"

#include <string>

namespace oit::illustration_buffer {

ShaderDefines ShaderVariant::defines() const {
  ShaderDefines d;
  const auto flag = [&d](bool on, const char* name) {
    if (on) d.push_back({name, "1"});
  };
  flag(ranged, "IB_RANGED");
  flag(arrays, "IB_ARRAYS");
  flag(fetch_cursor, "IB_FETCH_CURSOR");
  flag(listed, "IB_LISTED");
  flag(flat_color, "IB_FLAT_COLOR");
  flag(measure, "IB_MEASURE");
  flag(surface, "IB_SURFACE");
  flag(angle, "IB_ANGLE");
  flag(normal_variation, "IB_NORMAL_VARIATION");
  if (sort_array > 0) d.push_back({"IB_ARRAY", std::to_string(sort_array)});
  flag(dynamic_sort, "IB_DYNAMIC");
  flag(static_arrays, "IB_STATIC_ARRAYS");
  flag(truncates, "IB_TRUNCATES");
  flag(triangle_vertices, "IB_TRIANGLE_VERTICES");
  flag(merge, "IB_MERGE");
  if (group > 0) d.push_back({"IB_GROUP", std::to_string(group)});
  flag(track, "IB_TRACK");
  flag(alpha_seeds, "IB_ALPHA_SEEDS");
  flag(sweep_init, "IB_SWEEP_INIT");
  flag(adaptive, "IB_ADAPTIVE");
  flag(diffuse == Diffuse::worklist, "IB_WORKLIST");
  flag(diffuse == Diffuse::sweep, "IB_SWEEP");
  flag(diffuse == Diffuse::check, "IB_CHECK");
  flag(homogeneous_fields, "IB_HOMOGENEOUS_FIELDS");
  flag(modulate, "IB_MODULATE");
  if (modulate) d.push_back({"IB_PROFILE", std::to_string(profile)});
  flag(swept, "IB_SWEPT");
  flag(local_opacity, "IB_LOCAL_OPACITY");
  flag(ray_distance, "IB_RAY_DISTANCE");
  return d;
}

}  // namespace oit::illustration_buffer
