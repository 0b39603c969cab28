// Read-only views of fragData2, fragData3 and the input field
// range as buffer textures. On llvmpipe a texelFetch with per-invocation
// addresses is a vector gather, while an SSBO load with per-invocation
// addresses is a lane-by-lane loop; the per-fragment passes read their
// neighbours' records through these views (their writes still go to SSBOs).
layout(binding = IB_SEARCH_UNIT) uniform usamplerBuffer ib_search_view;     // RGBA32UI, 2 texels per IbSortedSearch (fragData2)
layout(binding = IB_FIELDS_UNIT) uniform samplerBuffer ib_fields_view;      // RGBA32F, the input field range
layout(binding = IB_SHADE_UNIT) uniform usamplerBuffer ib_shade_view;       // RGBA32UI, 2 texels per IbSortedShade (fragData3)
layout(binding = IB_HEAD_UNIT) uniform usamplerBuffer ib_head_view;         // R32UI, each pixel's first sorted fragment
layout(binding = IB_COUNT_UNIT) uniform usamplerBuffer ib_count_view;       // R32UI, each pixel's fragment count

// Members by texel: IbSortedSearch 0 key, 1 geometry; IbSortedShade 0 color, 1 links.
uvec4 ib_sorted_key(uint s) { return texelFetch(ib_search_view, int(s * 2u)); }
uvec4 ib_sorted_geometry(uint s) { return texelFetch(ib_search_view, int(s * 2u + 1u)); }
vec4 ib_sorted_color(uint s) { return uintBitsToFloat(texelFetch(ib_shade_view, int(s * 2u))); }
uvec4 ib_sorted_links(uint s) { return texelFetch(ib_shade_view, int(s * 2u + 1u)); }

// A pixel's sorted range [first, first + count).
uint ib_pixel_first(uint pixel) { return texelFetch(ib_head_view, int(pixel)).x; }
uint ib_pixel_count(uint pixel) { return texelFetch(ib_count_view, int(pixel)).x; }
// Position of sorted fragment `s` in its pixel's list (0 = nearest).
uint ib_layer_of(uint s, uint pixel) { return s - ib_pixel_first(pixel); }
