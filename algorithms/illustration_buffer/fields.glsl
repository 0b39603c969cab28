// The transparency fields of carnecky2013 section 5.1, one vec4 per sorted
// fragment: x = alpha (initial opacity, diffused by eq. 8), y = beta
// (silhouette field), z = gamma (halo field), w = boundary flags
// (IB_FIXED_BETA | IB_FIXED_GAMMA of bindings.h: the paper's b_beta = 0 / b_gamma = 0).
// b_alpha is 1 for every fragment (no rule of section 5.3 sets it).
// Two ranges ping-pong between the iterations (section 4.5, local operators).

layout(std430, binding = IB_FIELDS_IN_BINDING) readonly buffer IbFieldsIn { vec4 ib_fields_in[]; };
layout(std430, binding = IB_FIELDS_OUT_BINDING) writeonly buffer IbFieldsOut { vec4 ib_fields_out[]; };

uint ib_flags(vec4 field) { return uint(field.w); }
