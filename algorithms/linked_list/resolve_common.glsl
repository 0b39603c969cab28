// Shared by the resolve programs: sort keys and the float front-to-back blend.
#include "shaders/compose.glsl"
#include "algorithms/linked_list/nodes.glsl"

layout(location = 0) out vec4 out_color;

// Read-only views of the lists (see linked_list.cpp: a buffer texture fetch
// or image load is a vector gather on llvmpipe, an SSBO load is a loop over
// the lanes). A node is two RGBA32UI texels: colour bits, then the link.
// The nodes are read as an image: on llvmpipe (Mesa 22.3) imageLoad made
// the network resolve faster than texelFetch of the same buffer (the
// insertion resolve, bound by its local array, did not change; README).
#if defined(LL_COMPACT)
layout(binding = LINKED_LIST_NODES_IMAGE_UNIT, r32ui) readonly uniform uimageBuffer u_nodes;
#else
layout(binding = LINKED_LIST_NODES_IMAGE_UNIT, rgba32ui) readonly uniform uimageBuffer u_nodes;
#endif
layout(binding = LINKED_LIST_HEADS_UNIT) uniform usamplerBuffer u_heads;
layout(binding = LINKED_LIST_LENGTHS_UNIT) uniform usamplerBuffer u_lengths;

// The heads of the pixel's LL_HEADS lists (nodes.glsl), one RGBA32UI texel.
uvec4 heads_of(uint pixel) { return texelFetch(u_heads, int(pixel)); }
uint length_of(uint pixel) { return texelFetch(u_lengths, int(pixel)).x; }
#if defined(LL_COMPACT)
// y (the tie-break) is the node index: unique, but not stable across frames.
uvec4 link_of(uint node) {
  const int at = int(LL_NODE_WORDS * node);
  return uvec4(imageLoad(u_nodes, at).x, node, imageLoad(u_nodes, at + 2).x, 0u);
}
vec4 color_of(uint node) { return unpackUnorm4x8(imageLoad(u_nodes, int(LL_NODE_WORDS * node + 1u)).x); }
#else
uvec4 link_of(uint node) { return imageLoad(u_nodes, int(2u * node + 1u)); }
vec4 color_of(uint node) { return uintBitsToFloat(imageLoad(u_nodes, int(2u * node))); }
#endif

// A sort element: x = view depth bits mapped to unsigned order, y = stable
// triangle id (unique per pixel: the deterministic tie-break), z = node index.
uvec3 sort_element(uint node, uvec4 link) {
  return uvec3(oit_depth_order(link.x), link.y, node);
}

bool precedes(uvec3 a, uvec3 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }

vec3 accumulated = vec3(0.0);
float transmittance = 1.0;

// Front-to-back "under" in the reference's operation order, in float.
void blend(uint node) {
  const vec4 c = color_of(node);
  const float weight = transmittance * c.a;
  accumulated += weight * c.rgb;
  transmittance *= 1.0 - c.a;
}
