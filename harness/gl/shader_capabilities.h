#pragma once
// Defines every program is built with, from what the current context can
// do, so that a shader takes a faster path where the driver has one and the
// plain one elsewhere; build_program adds them (harness/gl/shader_program.h).
//
// OIT_SHADER_BALLOT: GL_ARB_shader_ballot and GL_ARB_gpu_shader_int64, for
// the subgroup-aggregated atomics of shaders/subgroup_atomics.glsl.
// OIT_SHADER_BALLOT=off in the environment leaves it out (read at every
// call), to measure what it saves or to step around a driver.
// OIT_INTERLOCK_ARB / OIT_INTERLOCK_NV / OIT_ORDERING_INTEL: the first of
// GL_ARB_fragment_shader_interlock, GL_NV_fragment_shader_interlock and
// GL_INTEL_fragment_shader_ordering the driver has, for the ordered per-pixel
// access of shaders/ordered_access.glsl.
#include <string>

#include "harness/gl/shader_defines.h"

namespace oit {

ShaderDefines capability_defines();

// The extension shaders/ordered_access.glsl uses on this context
// ("GL_ARB_fragment_shader_interlock", ...), or "" when it falls back to a
// per-pixel spin lock.
std::string ordered_access_extension();

// "subgroup atomics" or "plain atomics": which path the programs built now take.
std::string atomics_path();

}  // namespace oit
