// Ordered, exclusive access to one pixel's storage from a fragment shader,
// for techniques that read, modify and write a per-pixel structure in
// rasterisation order (multi-layer alpha blending, adaptive transparency).
// Include right after #version (it may enable extensions), after defining
// OIT_ORDERED_LOCK_BINDING, the binding of the lock buffer (used by the
// fallback only; declare and clear it either way).
//
// Where the driver has fragment shader interlock (gl/shader_capabilities.h
// defines OIT_INTERLOCK_ARB, OIT_INTERLOCK_NV or OIT_ORDERING_INTEL), the
// critical section runs between the extension's begin and end calls:
// exclusive per pixel and in primitive order. Those calls may not sit in
// flow control: write OIT_ORDERED(...) in main() itself, before any return.
//
// Elsewhere a per-pixel spin lock guards it. The acquiring invocation runs
// the critical section and releases the lock in the same loop iteration as
// the acquisition, so lanes of one subgroup that wait on each other cannot
// deadlock (the holder is never the lane left waiting), and the loop is
// bounded by OIT_SPIN_LIMIT attempts: an invocation that never acquires
// gives up, skips its critical section and counts itself in
// oit_lock_failures, which the technique reports as dropped fragments. A
// lock gives exclusion, not order: the result depends on which invocation
// comes first. On Mesa llvmpipe no failure can happen, see the README of
// multi_layer_alpha_blending ("Ordered access on llvmpipe").
#include "shaders/bindings.h"

#if defined(OIT_INTERLOCK_ARB)
#extension GL_ARB_fragment_shader_interlock : require
layout(pixel_interlock_ordered) in;
#define OIT_ORDERED(pixel, critical) { beginInvocationInterlockARB(); critical; endInvocationInterlockARB(); }
#elif defined(OIT_INTERLOCK_NV)
#extension GL_NV_fragment_shader_interlock : require
layout(pixel_interlock_ordered) in;
#define OIT_ORDERED(pixel, critical) { beginInvocationInterlockNV(); critical; endInvocationInterlockNV(); }
#elif defined(OIT_ORDERING_INTEL)
#extension GL_INTEL_fragment_shader_ordering : require
#define OIT_ORDERED(pixel, critical) { beginFragmentShaderOrderingINTEL(); critical; }
#else
#define OIT_SPIN_LOCK 1
#endif

// oit_lock_failures: invocations that gave up (spin lock only); then one
// lock word per pixel, 0 = free.
layout(std430, binding = OIT_ORDERED_LOCK_BINDING) coherent buffer OitPixelLocks {
  uint oit_lock_failures;
  uint oit_pixel_locks[];
};

#ifdef OIT_SPIN_LOCK
#define OIT_SPIN_LIMIT 65536u
#define OIT_ORDERED(pixel, critical) { \
    bool oit_done_ = false; \
    for (uint oit_attempt_ = 0u; !oit_done_ && oit_attempt_ < OIT_SPIN_LIMIT; ++oit_attempt_) { \
      if (atomicCompSwap(oit_pixel_locks[pixel], 0u, 1u) == 0u) { \
        critical; \
        memoryBarrierBuffer(); \
        atomicExchange(oit_pixel_locks[pixel], 0u); \
        oit_done_ = true; \
      } \
    } \
    if (!oit_done_) atomicAdd(oit_lock_failures, 1u); }
#endif
