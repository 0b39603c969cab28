// Final write into the harness's RGBA32F target, shared by every compose pass:
// the colour accumulated front to back (premultiplied) plus what the
// remaining transmittance lets through of the background; alpha = coverage.
#include "shaders/bindings.h"

layout(location = OIT_UNIFORM_BACKGROUND) uniform vec3 u_background;

vec4 oit_finish(vec3 accumulated, float transmittance) {
  return vec4(accumulated + transmittance * u_background, 1.0 - transmittance);
}
