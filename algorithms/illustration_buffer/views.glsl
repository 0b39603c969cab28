// Read-only views of fragData2, the triangle table and the input field
// range as buffer textures. On llvmpipe a texelFetch with per-invocation
// addresses is a vector gather, while an SSBO load with per-invocation
// addresses is a lane-by-lane loop; the per-fragment passes read their
// neighbours' records through these views (their writes still go to SSBOs).
layout(binding = IB_SEARCH_UNIT) uniform usamplerBuffer ib_search_view;     // RGBA32UI, 2 texels per IbSortedSearch (fragData2)
layout(binding = IB_TRIANGLES_UNIT) uniform usamplerBuffer ib_triangle_view; // RGBA32UI, one row per stable triangle id
layout(binding = IB_FIELDS_UNIT) uniform samplerBuffer ib_fields_view;      // RGBA32F, the input field range
layout(binding = IB_SHADE_UNIT) uniform usamplerBuffer ib_shade_view;       // RGBA32UI, 2 texels per IbSortedShade (fragData3)

// Members by texel: IbSortedSearch 0 key, 1 geometry; IbSortedShade 0 color, 1 links.
uvec4 ib_sorted_key(uint s) { return texelFetch(ib_search_view, int(s * 2u)); }
uvec4 ib_sorted_geometry(uint s) { return texelFetch(ib_search_view, int(s * 2u + 1u)); }
vec4 ib_sorted_color(uint s) { return uintBitsToFloat(texelFetch(ib_shade_view, int(s * 2u))); }
uvec4 ib_sorted_links(uint s) { return texelFetch(ib_shade_view, int(s * 2u + 1u)); }
