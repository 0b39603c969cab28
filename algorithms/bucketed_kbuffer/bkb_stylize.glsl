// Stylization (murray2016 5.2) of one stored fragment: the shaded colour is
// multiplied by a 1D transfer function indexed by kappa in [-1, 1]; the
// opacity is replaced by a 2D transfer function indexed by |kappa| and the
// normalised depth. Both are textures (built-in shapes from
// transfer_functions.cpp, or files read by transfer_files.cpp) sampled at
// texel centres so that the end points of each axis are exact.
// COLOR_TRANSFER = 0 or OPACITY_TRANSFER = 0 (the identity choices, no file)
// leave that part unchanged. Used by stylize.frag (slot_layout=full) and by
// neighbors.frag (slot_layout=paper: in place, as kappa is found).
layout(binding = BKB_COLOR_TRANSFER_UNIT) uniform sampler1D u_color_transfer;
layout(binding = BKB_OPACITY_TRANSFER_UNIT) uniform sampler2D u_opacity_transfer;

float texel_centre(float x, float size) { return (0.5 + clamp(x, 0.0, 1.0) * (size - 1.0)) / size; }

// The slot's packed RGBA8 colour after the transfer functions; `key`: the
// slot's shape-major key (its depth).
uint bkb_stylize(uint packed_color, float kappa, uint key) {
  vec4 color = unpackUnorm4x8(packed_color);
#if COLOR_TRANSFER
  float color_size = float(textureSize(u_color_transfer, 0));
  color.rgb = clamp(color.rgb * texture(u_color_transfer, texel_centre(0.5 * kappa + 0.5, color_size)).rgb, 0.0, 1.0);
#endif
#if OPACITY_TRANSFER
  vec2 opacity_size = vec2(textureSize(u_opacity_transfer, 0));
  color.a = texture(u_opacity_transfer, vec2(texel_centre(abs(kappa), opacity_size.x),
                                             texel_centre(bkb_depth_unit(key), opacity_size.y))).r;
#endif
  return packUnorm4x8(color);
}
