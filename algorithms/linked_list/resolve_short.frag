#version 450 core
// Resolve draw for lists of 0 or 1 fragments (group_by_length=true): there
// is nothing to sort, so the pixel is the background or its one fragment
// under it, with no local array and no sort. Every longer list is discarded
// here and resolved by resolve.frag.
#include "algorithms/linked_list/resolve_common.glsl"

void main() {
  const uint pixel = ll_pixel();
  const uint length = length_of(pixel);
  if (length > 1u) discard;
  if (length == 1u) blend(head_of(pixel));
  out_color = oit_finish(accumulated, transmittance);
}
