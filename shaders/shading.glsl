// The shading function shared by every technique: each fragment gets the same
// straight RGBA whatever the technique, so images differ only by how
// fragments are stored, ordered and composited.
#include "shaders/bindings.h"

in vec3 v_view_position;
in vec3 v_view_normal;
flat in vec4 v_color;
flat in uint v_object_id;
flat in uint v_surface_id;
in vec2 v_uv;
in float v_mean_curvature;  // analytic, in scene units, where the scene knows it

#ifdef OIT_SCENE_LIT
// The scene's shading, compiled in (harness/gl/shader_program.h,
// SceneShading): an unlit program reads no normal or position to shade.
bool oit_scene_lit() { return OIT_SCENE_LIT != 0; }
#else
layout(location = OIT_UNIFORM_LIT) uniform bool u_lit;
bool oit_scene_lit() { return u_lit; }
#endif

layout(binding = OIT_UNIT_TRIANGLE_IDS) uniform usamplerBuffer oit_triangle_ids;

layout(location = OIT_UNIFORM_PIXEL_ORIGIN) uniform ivec2 u_pixel_origin;

// This fragment's pixel in the whole image, also when the harness renders
// the frame in screen tiles (gl_FragCoord is then the tile's): what a
// per-pixel random seed must use so that tiled and untiled images agree.
ivec2 oit_image_pixel() { return ivec2(gl_FragCoord.xy) + u_pixel_origin; }

// Stable triangle id: the deterministic depth tie-break, unchanged when the
// triangles are submitted in another order.
uint oit_triangle_id() { return texelFetch(oit_triangle_ids, gl_PrimitiveID).x; }

// Distance along the view direction (positive in front of the camera).
float oit_view_depth() { return -v_view_position.z; }

vec3 oit_view_normal() {
  vec3 n = normalize(v_view_normal);
  // Two-sided: the normal faces the viewer.
  return gl_FrontFacing ? n : -n;
}

// What the lighting multiplies the material colour's rgb by: a two-sided
// headlight, ambient 0.25 + diffuse 0.75 * |n.v|; 1 for unlit scenes.
float oit_light_factor() {
  if (!oit_scene_lit()) return 1.0;
  vec3 to_eye = normalize(-v_view_position);
  float lambert = abs(dot(normalize(v_view_normal), to_eye));
  return 0.25 + 0.75 * lambert;
}

// Straight (not premultiplied) colour and opacity of this fragment: unlit
// scenes output the material colour exactly (the flat v_color, SceneGpu's
// flat-colour table), lit ones its rgb times oit_light_factor(). A
// technique that stores the factor can rebuild the colour bit for bit.
vec4 oit_shade() {
  if (!oit_scene_lit()) return v_color;
  return vec4(v_color.rgb * oit_light_factor(), v_color.a);
}
