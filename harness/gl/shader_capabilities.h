#pragma once
// Defines every program is built with, from what the current context can
// do, so that a shader takes a faster path where the driver has one and the
// plain one elsewhere; build_program adds them (shader_program.h).
//
// OIT_SHADER_BALLOT: GL_ARB_shader_ballot and GL_ARB_gpu_shader_int64, for
// the subgroup-aggregated atomics of shaders/subgroup_atomics.glsl.
// OIT_SHADER_BALLOT=off in the environment leaves it out (read at every
// call), to measure what it saves or to step around a driver.
#include <string>

#include "gl/shader_program.h"

namespace oit {

ShaderDefines capability_defines();

// "subgroup atomics" or "plain atomics": which path the programs built now take.
std::string atomics_path();

}  // namespace oit
