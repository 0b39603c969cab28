// Counters that every fragment bumps (a pool's next free node, a count of
// dropped fragments) are one memory word hit by every shader invocation. On
// llvmpipe each SIMD lane's atomic is a locked instruction on a cache line
// that the raster threads pass back and forth: at 32 layers, 256x256, the
// linked-list fill spent about a third of its time there. Where the driver
// has GL_ARB_shader_ballot (and 64-bit integers for its masks), the build
// defines OIT_SHADER_BALLOT (gl/shader_capabilities.h) and the active
// invocations of a subgroup add their total once, through their lowest
// lane, each taking its own offset (its rank among them): one atomic per
// subgroup instead of one per invocation, and the same values. Helper
// invocations take part in neither (their side effects are discarded).
//
// For fragment shaders (the macros read gl_HelperInvocation). Include first,
// right after #version: it may enable extensions.
#if defined(OIT_SHADER_BALLOT)
#extension GL_ARB_shader_ballot : require
#extension GL_ARB_gpu_shader_int64 : require

uint oit_lane_count(uint64_t lanes) {
  const uvec2 words = unpackUint2x32(lanes);
  return uint(bitCount(words.x) + bitCount(words.y));
}
uint oit_lowest_lane(uint64_t lanes) {
  const uvec2 words = unpackUint2x32(lanes);
  return words.x != 0u ? uint(findLSB(words.x)) : 32u + uint(findLSB(words.y));
}

// index = atomicAdd(counter, 1u), for every invocation that reaches it.
#define OIT_ATOMIC_APPEND(counter, index) { \
    const uint64_t oit_lanes_ = ballotARB(!gl_HelperInvocation); \
    const uint oit_rank_ = oit_lane_count(oit_lanes_ & gl_SubGroupLtMaskARB); \
    uint oit_first_ = 0u; \
    if (oit_rank_ == 0u && !gl_HelperInvocation) oit_first_ = atomicAdd(counter, oit_lane_count(oit_lanes_)); \
    index = readInvocationARB(oit_first_, oit_lowest_lane(oit_lanes_)) + oit_rank_; }
// atomicAdd(counter, 1u) without the result.
#define OIT_ATOMIC_COUNT(counter) { \
    const uint64_t oit_lanes_ = ballotARB(!gl_HelperInvocation); \
    if (!gl_HelperInvocation && oit_lane_count(oit_lanes_ & gl_SubGroupLtMaskARB) == 0u) \
      atomicAdd(counter, oit_lane_count(oit_lanes_)); }
#else
#define OIT_ATOMIC_APPEND(counter, index) { index = atomicAdd(counter, 1u); }
#define OIT_ATOMIC_COUNT(counter) { atomicAdd(counter, 1u); }
#endif

// atomicMax(counter, value) for a maximum that rarely grows (the longest
// list): a plain read first, so nearly every invocation only reads the
// shared word and the cache line is not written back and forth. A stale
// read is never too large (the word only grows), so no maximum is missed.
#define OIT_ATOMIC_RAISE(counter, value) { \
    const uint oit_value_ = (value); \
    if (oit_value_ > counter) atomicMax(counter, oit_value_); }
