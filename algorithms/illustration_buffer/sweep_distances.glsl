// diffusion=sweep works on hop distances, not on beta and gamma. Eq. 9
// from initial values of 0 or 1 (stylize_init.comp) only ever gives a
// fragment the value F(d) of its nearest seed, d links away through unfixed
// fragments, F(0) = 1 and F(d) = F(d - 1) - lambda in float, or 0 where no
// seed is near enough (F(d) <= 0): the max over paths of eq. 9's decrements
// is F of the shortest path. So the sweeps carry d, and the compose turns
// it into F(d) (a table the host computes with the same float subtraction):
// the same values bit for bit, from one 4-byte read per neighbour where the
// fields take a 16-byte one, and no field ranges written at all.
//
// One uint per sorted fragment (bindings.h), beta's distance in bits 0-15
// and gamma's in 16-31; each half: the bit IB_DISTANCE_FIXED for a boundary
// condition (a seed, fixed at 1: distance 0; or a field fixed at 0:
// IB_DISTANCE_FAR), and the distance, IB_DISTANCE_FAR where no seed has
// reached it.

layout(std430, binding = IB_DISTANCES_BINDING) buffer IbDistances { uint ib_distances[]; };
layout(binding = IB_DISTANCES_UNIT) uniform usamplerBuffer ib_distances_view;

uint ib_pack_distances(uvec2 distances) { return distances.x | (distances.y << 16); }
uvec2 ib_unpack_distances(uint both) { return uvec2(both & 0xffffu, both >> 16); }

#ifdef IB_SWEPT  // the compose of a frame whose diffusion swept
// F(d) for d < ib.table_size, beta's then gamma's (the host's table); 0 beyond.
layout(binding = IB_FIELD_TABLE_UNIT) uniform samplerBuffer ib_field_table;

// Beta and gamma of sorted fragment s, from its distances.
vec2 ib_swept_fields(uint s) {
  const uvec2 distances = ib_unpack_distances(texelFetch(ib_distances_view, int(s)).x) & IB_DISTANCE_FAR;
  const bvec2 near = lessThan(distances, uvec2(ib.table_size));
  return vec2(near.x ? texelFetch(ib_field_table, int(distances.x)).x : 0.0,
              near.y ? texelFetch(ib_field_table, int(ib.table_size + distances.y)).x : 0.0);
}
#endif
