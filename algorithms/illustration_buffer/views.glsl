// Read-only views of fragData2, the triangle table and the input field
// range as buffer textures. On llvmpipe a texelFetch with per-invocation
// addresses is a vector gather, while an SSBO load with per-invocation
// addresses is a lane-by-lane loop; the per-fragment passes read their
// neighbours' records through these views (their writes still go to SSBOs).
layout(binding = 0) uniform usamplerBuffer ib_sorted_view;   // RGBA32UI, 4 texels per IbSorted
layout(binding = 1) uniform usamplerBuffer ib_triangle_view; // RGBA32UI, one row per stable triangle id
layout(binding = 2) uniform samplerBuffer ib_fields_view;    // RGBA32F, the input field range

// Members of IbSorted by texel: 0 color, 1 key, 2 geometry, 3 links.
uvec4 ib_sorted_key(uint s) { return texelFetch(ib_sorted_view, int(s * 4u + 1u)); }
uvec4 ib_sorted_geometry(uint s) { return texelFetch(ib_sorted_view, int(s * 4u + 2u)); }
uvec4 ib_sorted_links(uint s) { return texelFetch(ib_sorted_view, int(s * 4u + 3u)); }
