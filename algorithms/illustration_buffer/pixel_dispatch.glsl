// The per-pixel passes (sort.comp, neighbors_triangle_index.comp): one
// invocation per pixel, in workgroups of 64. Over the whole image, or
// (IB_LISTED, storage=linearized or arrays, whose counts the host holds) over the
// host's list of the pixels that hold a fragment. Llvmpipe runs a shader's
// every path for each group of 8 invocations it is dispatched over, empty
// pixels included (branches are masked, not skipped), so a dispatch over
// the covered pixels alone costs what they need (README, Counters and work saved).
layout(local_size_x = 8, local_size_y = 8) in;
#ifdef IB_LISTED
layout(binding = IB_LISTED_PIXELS_UNIT) uniform usamplerBuffer ib_listed_pixels;  // R32UI, in raster order
#endif

// This invocation's pixel; false when it has none (past the image or the list).
bool ib_invocation_pixel(out uint pixel) {
#ifdef IB_LISTED
  const uint entry = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 64u + gl_LocalInvocationIndex;
  pixel = texelFetch(ib_listed_pixels, int(entry)).x;  // past the list: 0, unused
  return entry < ib.listed_pixels;
#else
  pixel = gl_GlobalInvocationID.y * uint(ib.width) + gl_GlobalInvocationID.x;
  return gl_GlobalInvocationID.x < uint(ib.width) && gl_GlobalInvocationID.y < uint(ib.height);
#endif
}
