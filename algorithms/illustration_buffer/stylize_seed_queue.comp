#version 450 core
// The first diffusion step's worklist (skip_converged), one invocation per
// pixel: pixel p is listed when p or one of its 4 adjacent pixels holds a
// fragment that stylize_init marked as a seed (a fragment whose initial
// value can move a linked neighbour: stylize_init.comp). Each pixel decides
// for itself, so no stamp is needed to list it once.
layout(local_size_x = 8, local_size_y = 8) in;
#include "algorithms/illustration_buffer/ib_storage.glsl"
#include "algorithms/illustration_buffer/worklist.glsl"

layout(binding = IB_SEEDS_UNIT) uniform usamplerBuffer ib_seeds_view;  // R32UI, 1 = a seed in the pixel

bool seeded(int x, int y) {
  if (x < 0 || y < 0 || x >= ib.width || y >= ib.height) return false;
  return texelFetch(ib_seeds_view, y * ib.width + x).x != 0u;
}

void main() {
  const int x = int(gl_GlobalInvocationID.x), y = int(gl_GlobalInvocationID.y);
  if (x >= ib.width || y >= ib.height) return;
  if (seeded(x, y) || seeded(x - 1, y) || seeded(x + 1, y) || seeded(x, y - 1) || seeded(x, y + 1))
    ib_append(uint(y) * uint(ib.width) + uint(x));
}
