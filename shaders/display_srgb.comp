#version 450 core
// The viewer's scene area as the PNG writer writes it (harness/output/image.h,
// PngEncoding::display): the linear image's RGB clamped and sRGB-encoded
// (IEC 61966-2-1), alpha 1, into an RGBA8 image the window copies 1:1.
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D u_linear;
layout(binding = 0, rgba8) uniform writeonly image2D u_display;

vec3 srgb_encode(vec3 linear) {
  // NaN -> 0, as on the CPU (max/min would pass a NaN on).
  vec3 c = mix(clamp(linear, 0.0, 1.0), vec3(0.0), isnan(linear));
  return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, greaterThan(c, vec3(0.0031308)));
}

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(u_display)))) return;
  imageStore(u_display, p, vec4(srgb_encode(texelFetch(u_linear, p, 0).rgb), 1.0));
}
