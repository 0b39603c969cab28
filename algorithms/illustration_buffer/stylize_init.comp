#version 450 core
// Initial and boundary conditions, one invocation per sorted fragment
// (fields_init.glsl; neighbors=triangle_index sets them in its search).
#include "algorithms/illustration_buffer/ib_storage.glsl"
#include "algorithms/illustration_buffer/per_fragment.glsl"
#include "algorithms/illustration_buffer/fields.glsl"
#include "algorithms/illustration_buffer/views.glsl"
#include "algorithms/illustration_buffer/fields_init.glsl"

// The layer of the neighbour behind link d (the adjacent pixel's list).
uvec4 neighbor_layers(uvec4 links, uint pixel) {
  const uvec4 adjacent = ib_adjacent_pixels(pixel);
  uvec4 layers = uvec4(0u);
  for (int d = 0; d < 4; ++d)
    if (links[d] < IB_OFF_IMAGE) layers[d] = ib_layer_of(links[d], adjacent[d]);
  return layers;
}

void main() {
  const uint s = ib_fragment_index();
  if (s >= u_fragments) return;
  const uint pixel = ib_sorted_key(s).w;
  const uvec4 links = ib_sorted_links(s);
  const float alpha = ib_initial_alpha(ib_sorted_color(s).a, ib_pixel_count(pixel));
  const vec4 fields = ib_initial_fields(alpha, ib_layer_of(s, pixel), links, neighbor_layers(links, pixel));
  ib_fields_out[s] = fields;
#ifdef IB_TRACK
  ib_seed_diffusion(fields, links, pixel);
#endif
}
