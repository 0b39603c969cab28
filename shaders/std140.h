// Included by a technique's bindings.h before it declares its parameter
// block's struct (harness/gl/uniform_block.h), so that one declaration
// serves GLSL and C++: C++ learns GLSL's `uint`, and the struct lands in
// namespace oit there (OIT_STD140_BEGIN / OIT_STD140_END around it) and at
// global scope in GLSL, which has no namespaces. Members are int, uint and
// float only (a GLSL bool is 4 bytes, a C++ one 1: use a uint), padded
// with unused members to a multiple of 16 bytes, which UniformBlock checks.
#ifndef OIT_SHADERS_STD140_H
#define OIT_SHADERS_STD140_H

#ifdef __cplusplus
#include <cstdint>
namespace oit {
using uint = std::uint32_t;
}
#define OIT_STD140_BEGIN namespace oit {
#define OIT_STD140_END }
#else
#define OIT_STD140_BEGIN
#define OIT_STD140_END
#endif

#endif
