// linearized_fragment_buffer: the GPU prefix sum against the CPU over three
// levels, every sort and resolve option against the exact reference (32
// quads, spheres, uneven random quads, shuffled submission, lists beyond the
// largest network), and its memory: exactly the frame's fragments, never an
// overflow.
#include <gtest/gtest.h>

#include <numeric>
#include <random>

#include "algorithms/linearized_fragment_buffer/prefix_sum.h"
#include "harness/gl/check.h"
#include "harness/gl/context.h"
#include "tests/gl_fixture.h"

namespace oit {
namespace {

// Float blending of up to 136 layers against the reference's double blend.
constexpr double kFloatTolerance = 1e-5;

// sort x block size x backwards allocation x node layout x fill x scan: the
// network with and without length classes, register blocks of 8 and 16 (two
// and four blocks on 32 layers), and blocks without classes; on unlit scenes
// (quads, random quads) flat-colour 8-byte nodes by default, 24-byte nodes
// with flat_color_nodes=false; slots by framebuffer fetch and by atomics,
// offsets summed on the host and by the compute scan; flat keys as one
// uint64 and as two 32-bit words.
const std::vector<RawParams> kOptions = {
    {{"sort", "network"}},
    {{"sort", "network"}, {"backwards_allocation", "false"}},
    {{"sort", "register_block"}, {"block_size", "8"}},
    {{"sort", "register_block"}, {"block_size", "16"}},
    {{"sort", "register_block"}, {"block_size", "8"}, {"backwards_allocation", "false"}},
    {{"sort", "network"}, {"flat_color_nodes", "false"}},
    {{"sort", "register_block"}, {"block_size", "8"}, {"flat_color_nodes", "false"}},
    // The slot by image atomic and the offsets by compute scan (the GPU
    // paths; fill=auto and scan=auto take the others on llvmpipe).
    {{"sort", "network"}, {"fill", "atomic"}, {"scan", "compute"}},
    {{"sort", "register_block"}, {"block_size", "8"}, {"fill", "atomic"}, {"flat_color_nodes", "false"}},
    {{"sort", "network"}, {"scan", "compute"}, {"flat_color_nodes", "false"}},
    {{"sort", "network"}, {"fill", "framebuffer_fetch"}, {"scan", "host"}},
    // Flat keys as two 32-bit words (key_format=auto takes uint64 on llvmpipe).
    {{"sort", "network"}, {"key_format", "uint32_pair"}},
    {{"sort", "register_block"}, {"block_size", "8"}, {"key_format", "uint32_pair"}}};

// kOptions that this device can run: fill=framebuffer_fetch needs
// GL_EXT_shader_framebuffer_fetch, which llvmpipe has (so CI runs every
// option) and NVIDIA's desktop GL has not.
std::vector<RawParams> runnable_options() {
  test::gl_context();
  std::vector<RawParams> options;
  for (const RawParams& params : kOptions) {
    const auto fill = params.find("fill");
    if (fill == params.end() || fill->second != "framebuffer_fetch" || test::gl_context().device().framebuffer_fetch)
      options.push_back(params);
  }
  return options;
}

bool flat_nodes(const RawParams& params) {
  const auto it = params.find("flat_color_nodes");
  return it == params.end() || it->second == "true";
}

std::string describe(const RawParams& params) {
  std::string text;
  for (const auto& [name, value] : params) text += name + "=" + value + " ";
  return text;
}

TEST(LinearizedFragmentBufferPrefixSum, EqualsTheCpuSumOverThreeLevelsWithLengthsAndLongestList) {
  test::gl_context();
  // 1500 x 800 pixels + 1: 1172 blocks of 1024, then 2, then 1.
  const int width = 1500, height = 800;
  const size_t pixels = size_t(width) * size_t(height);
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> count(0, 40);
  std::vector<float> counts(pixels);
  for (float& c : counts) c = float(count(rng));
  Texture texture = make_texture_2d(GL_R32F, width, height);
  glTextureSubImage2D(texture.id(), 0, 0, 0, width, height, GL_RED, GL_FLOAT, counts.data());
  lfb::PrefixSum sum;
  sum.resize(pixels);
  counts[pixels / 3] = 77.0f;  // the longest list, in a workgroup of its own
  glTextureSubImage2D(texture.id(), 0, 0, 0, width, height, GL_RED, GL_FLOAT, counts.data());
  EXPECT_EQ(sum.bytes_allocated(), (1172u + 2u + 1u) * 4u + 4u);
  Buffer offsets = make_buffer(GLsizeiptr((pixels + 1) * 4));
  Buffer lengths = make_buffer(GLsizeiptr(pixels * 4));
  sum.scan_counts(texture, width, offsets, lengths);
  const lfb::PrefixSum::Summary summary = sum.read_summary(offsets);
  EXPECT_EQ(summary.longest, 77u);
  std::vector<uint32_t> gpu(pixels + 1);
  glGetNamedBufferSubData(offsets.id(), 0, GLsizeiptr(gpu.size() * 4), gpu.data());
  gl_check("reading the prefix sum back");
  uint32_t expected = 0;
  for (size_t i = 0; i <= pixels; ++i) {
    ASSERT_EQ(gpu[i], expected) << "offset " << i;
    if (i < pixels) expected += uint32_t(counts[i]);
  }
  EXPECT_EQ(summary.total, expected);
  std::vector<uint32_t> gpu_lengths(pixels);
  glGetNamedBufferSubData(lengths.id(), 0, GLsizeiptr(gpu_lengths.size() * 4), gpu_lengths.data());
  for (size_t i = 0; i < pixels; ++i) ASSERT_EQ(gpu_lengths[i], uint32_t(counts[i])) << "length " << i;
}

TEST(LinearizedFragmentBuffer, EveryOptionMatchesTheReferenceOnThirtyTwoQuadsWithExactMemory) {
  const uint64_t w = 48, h = 48, pixels = w * h, fragments = 32 * pixels;
  for (const RawParams& params : runnable_options()) {
    const std::string what = describe(params);
    const RunResult r = test::render_once("linearized_fragment_buffer", params, "quads", {{"layers", "32"}}, 48, 48);
    ASSERT_TRUE(r.error.has_value()) << what;
    EXPECT_LT(r.error->max_abs, kFloatTolerance) << what;
    EXPECT_EQ(r.counters.fragments_stored, fragments) << what;
    EXPECT_EQ(r.counters.fragments_dropped, 0u) << what;
    EXPECT_EQ(r.counters.overflow_retries, 0u) << what;
    EXPECT_EQ(r.counters.passes, 2u) << what << ": the count and the fill";
    // 24 B per fragment (8 B and the 64 triangles' flat colours, 16 B
    // each, with flat-colour nodes), 16 B per pixel (count, offset, length
    // and fill cursor, a buffer or the R32UI target of the framebuffer-fetch
    // fill), the overflow word and the total, the prefix sum's block totals
    // (2305 values: 3 blocks, then 1) and its longest-list word, and one
    // length class (every list is 32 long: one full-screen draw).
    const uint64_t tiles = (w / 4) * (h / 4);
    const uint64_t nodes = flat_nodes(params) ? 8 * fragments + 64 * 16 : 24 * fragments;
    const uint64_t per_pixel = 16;
    EXPECT_EQ(r.counters.bytes_allocated, nodes + per_pixel * pixels + 8 + (3 + 1 + 1) * 4 + (16 + 4 * tiles)) << what;
    EXPECT_EQ(find_figure(r.counters.extra, "node_bytes"), flat_nodes(params) ? 8.0 : 24.0) << what;
  }
}

TEST(LinearizedFragmentBuffer, EveryOptionMatchesTheReferenceOnSpheresAndUnevenLists) {
  for (const RawParams& params : runnable_options()) {
    const std::string what = describe(params);
    const RunResult spheres = test::render_once("linearized_fragment_buffer", params, "spheres", {}, 48, 48);
    EXPECT_LT(spheres.error->max_abs, kFloatTolerance) << what << "spheres";
    // The spheres are lit: their colour is not the triangle's, so the nodes keep it.
    EXPECT_EQ(find_figure(spheres.counters.extra, "node_bytes"), 24.0) << what;
    EXPECT_EQ(spheres.counters.fragments_stored, spheres.scene_fragments) << what;
    // Lists of 2..23 fragments: classes 1, 8, 16 and 32; 37x29 cuts tiles at the edges.
    const RunResult uneven = test::render_once("linearized_fragment_buffer", params, "random_quads", {}, 37, 29);
    ASSERT_GT(uneven.max_depth_complexity, 16u);
    EXPECT_LT(uneven.error->max_abs, kFloatTolerance) << what << "random_quads";
    EXPECT_EQ(uneven.counters.fragments_stored, uneven.scene_fragments) << what;
  }
}

TEST(LinearizedFragmentBuffer, EveryOptionIsOrderIndependent) {
  for (const RawParams& params : runnable_options()) {
    const RunResult r = test::harness().run(
        test::one_frame("linearized_fragment_buffer", params, "quads", {{"layers", "32"}}, 48, "shuffled:7"));
    ASSERT_EQ(r.status, RunStatus::ok) << r.message;
    EXPECT_LT(r.error->max_abs, kFloatTolerance) << describe(params);
  }
}

TEST(LinearizedFragmentBuffer, AutoFillScanAndKeyFormatPickTheDevicesPaths) {
  test::gl_context();
  const bool fetch = epoxy_has_gl_extension("GL_EXT_shader_framebuffer_fetch");
  const bool software = test::gl_context().device().software;
  const bool int64 = epoxy_has_gl_extension("GL_ARB_gpu_shader_int64");
  const RunResult r = test::render_once("linearized_fragment_buffer", {}, "quads", {{"layers", "4"}}, 16, 16);
  EXPECT_EQ(find_figure(r.counters.extra, "framebuffer_fetch_fill"), fetch ? 1.0 : 0.0);
  EXPECT_EQ(find_figure(r.counters.extra, "host_scan"), software ? 1.0 : 0.0);
  EXPECT_EQ(find_figure(r.counters.extra, "uint64_keys"), int64 ? 1.0 : 0.0);
  const RunResult atomic = test::render_once("linearized_fragment_buffer", {{"fill", "atomic"}, {"scan", "compute"}},
                                             "quads", {{"layers", "4"}}, 16, 16);
  EXPECT_EQ(find_figure(atomic.counters.extra, "framebuffer_fetch_fill"), 0.0);
  EXPECT_EQ(find_figure(atomic.counters.extra, "host_scan"), 0.0);
  // Lit spheres keep 24-byte nodes: never 64-bit keys.
  const RunResult lit = test::render_once("linearized_fragment_buffer", {{"key_format", "uint64"}}, "spheres", {}, 16, 16);
  EXPECT_EQ(find_figure(lit.counters.extra, "uint64_keys"), 0.0);
}

TEST(LinearizedFragmentBuffer, ListsBeyondTheLargestNetworkAreSortedInRegisterBlocks) {
  // 136 layers: beyond the 128-element network, sorted in 9 blocks of 16
  // (sort=network) or 17 blocks of 8, and merged.
  for (const RawParams& params : {RawParams{{"sort", "network"}}, RawParams{{"sort", "register_block"}, {"block_size", "8"}}}) {
    const RunResult r = test::render_once("linearized_fragment_buffer", params, "quads",
                                          {{"layers", "136"}, {"alpha", "0.05"}}, 8, 8);
    EXPECT_EQ(r.counters.fragments_stored, 136u * 64u) << describe(params);
    EXPECT_LT(r.error->max_abs, kFloatTolerance) << describe(params);
  }
}

}  // namespace
}  // namespace oit
