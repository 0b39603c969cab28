// The linearized fragment buffer (Knowles et al. 2012): the fragments of
// pixel p lie in slots [offset[p], offset[p+1]) of one array of 24-byte
// nodes: the sort key (view depth in unsigned order, stable triangle id) and
// the straight RGBA colour as float bits, three RG32UI texels.
// LFB_FLAT_COLOR (unlit scenes: every fragment has its triangle's flat
// colour): 8-byte nodes, the key alone; the colour is fetched by triangle id
// from the scene's flat-colour table (SceneGpu::flat_colors_view). One array, not
// keys and colours apart: the fill's scattered writes then touch one or two
// cache lines per fragment instead of two or three, and the resolve reads
// the colour next to the key it sorted (README, "Node: 24 bytes").
#include "shaders/pixel_storage.glsl"
#include "algorithms/linearized_fragment_buffer/bindings.h"

layout(std140, binding = LFB_PARAMS_BLOCK) uniform LfbBlock { LfbParams lfb; };

#if defined(LFB_FLAT_COLOR)
#define LFB_NODE_TEXELS 1u
#else
#define LFB_NODE_TEXELS 3u
#endif
// Node s: LFB_NODE_TEXELS RG32UI texels from that many times s: the key,
// then (unless flat) the colour bits (r, g), (b, a).
int lfb_key_texel(uint slot) { return int(LFB_NODE_TEXELS * slot); }

// The key's texel. LFB_KEY64 (flat nodes on a device with 64-bit integers,
// key_format): the fill writes the key as one uint64, view depth in the high
// word and triangle id in the low, so the sort compares it with one 64-bit
// min/max; in memory (little-endian) the texel is then (id, depth). Else
// the texel is (depth, id).
#if defined(LFB_KEY64)
uvec2 lfb_key_from_texel(uvec2 texel) { return texel.yx; }
uvec4 lfb_texel_from_key(uvec2 key) { return key.yxxx; }
#else
uvec2 lfb_key_from_texel(uvec2 texel) { return texel; }
uvec4 lfb_texel_from_key(uvec2 key) { return key.xyyy; }
#endif

