#version 450 core
// The one vertex shader every geometry pass uses.
#include "shaders/bindings.h"

layout(location = OIT_ATTRIB_POSITION) in vec3 a_position;
layout(location = OIT_ATTRIB_NORMAL) in vec3 a_normal;
layout(location = OIT_ATTRIB_COLOR) in vec4 a_color;
layout(location = OIT_ATTRIB_OBJECT_ID) in uint a_object_id;
layout(location = OIT_ATTRIB_SURFACE_ID) in uint a_surface_id;
layout(location = OIT_ATTRIB_UV) in vec2 a_uv;
layout(location = OIT_ATTRIB_MEAN_CURVATURE) in float a_mean_curvature;

layout(location = OIT_UNIFORM_VIEW) uniform mat4 u_view;
layout(location = OIT_UNIFORM_PROJECTION) uniform mat4 u_projection;

out vec3 v_view_position;
out vec3 v_view_normal;
flat out vec4 v_color;
flat out uint v_object_id;
flat out uint v_surface_id;
out vec2 v_uv;
out float v_mean_curvature;

void main() {
  vec4 view_position = u_view * vec4(a_position, 1.0);
  v_view_position = view_position.xyz;
  v_view_normal = mat3(u_view) * a_normal;
  v_color = a_color;
  v_object_id = a_object_id;
  v_surface_id = a_surface_id;
  v_uv = a_uv;
  v_mean_curvature = a_mean_curvature;
  gl_Position = u_projection * view_position;
}
