#pragma once
// The one place that pulls in the GL loader (libepoxy resolves core and
// extension entry points for both EGL and GLFW contexts).
#include <epoxy/gl.h>
