// reference: the exact image. Captures every fragment in per-pixel linked
// lists (the pool grows and the frame is re-rendered when it overflows),
// orders each pixel's fragments by (view depth, stable triangle id) and
// blends them front to back in double precision. The resolve's local array
// is compiled for the longest list of the frame, so nothing is truncated.
// Lists longer than kMaxGpuListLength are resolved on the CPU with the same
// double-precision arithmetic: Mesa 22.3 llvmpipe returned wrong images for
// local arrays of 1024 entries (measured: 513 layers composited one layer).
#include <algorithm>
#include <bit>
#include <cstring>
#include <map>
#include <stdexcept>
#include <vector>

#include "harness/toolkit/fragment_pool.h"
#include "harness/toolkit/pixel_lists.h"
#include "harness/toolkit/technique.h"
#include "harness/toolkit/passes.h"
#include "harness/gl/check.h"
#include "harness/gl/shader_program.h"
#include "harness/gl/uniform_block.h"
#include "algorithms/reference/bindings.h"

namespace oit {
namespace {

constexpr GLsizeiptr kNodeBytes = 32;  // ReferenceNode in reference_nodes.glsl
// Longest list the GPU resolve handles; longer frames resolve on the CPU.
constexpr uint32_t kMaxGpuListLength = 512;

class Reference final : public Technique {
 public:
  explicit Reference(const ParamSet& params)
      : nodes_per_pixel_(params.integer("initial_nodes_per_pixel")),
        fill_(build_geometry_program("algorithms/reference/fill.frag")),
        lists_({REFERENCE_HEADS_BINDING, REFERENCE_NODES_BINDING, REFERENCE_COUNTER_BINDING,
                REFERENCE_LENGTHS_BINDING},
               2 * sizeof(GLuint)),
        pool_("reference", FragmentPool::Sizing::previous_frame, kNodeBytes,
              [this](uint64_t capacity) { allocate_pool(capacity); }) {}

  void resize(int width, int height) override {
    width_ = width;
    height_ = height;
    params_.values.width = width;
    lists_.heads = make_buffer(GLsizeiptr(width) * height * 4);
    lists_.lengths = make_buffer(GLsizeiptr(width) * height * 4);
    pool_.reset(uint64_t(width) * uint64_t(height) * uint64_t(nodes_per_pixel_));
    no_attachments_ = make_attachmentless_framebuffer(width, height);
  }

  void render(const Frame& frame) override {
    GLuint counts[2] = {0, 0};  // node_count, max_length
    passes_ = lists_.fill_until_fits(frame, pool_, [&] {
      params_.upload();  // the capacity may have grown since the last fill
      draw_scene_pass(frame, fill_, no_attachments_);
    }, counts);
    max_length_ = counts[1];
    stored_ = counts[0];
    auto compose = frame.clock.stage("compose");
    if (max_length_ > kMaxGpuListLength) {
      resolve_on_cpu(frame);
      return;
    }
    lists_.bind();
    draw_fullscreen_pass(frame, resolve_program(max_length_));
  }

  TechniqueCounters counters() const override {
    TechniqueCounters c;
    c.bytes_allocated = uint64_t(width_) * uint64_t(height_) * 8 + pool_.capacity() * uint64_t(kNodeBytes) + 8;
    c.fragments_stored = stored_;
    c.passes = passes_;
    c.overflow_retries = pool_.overflow_retries();
    return c;
  }

 private:
  // The same gather, order and double-precision blend as resolve.frag, on
  // the CPU, for frames whose longest list exceeds the GPU resolve's array.
  void resolve_on_cpu(const Frame& frame) {
    struct Node {
      float color[4];
      uint32_t depth_bits, triangle_id, next, unused;
    };
    static_assert(sizeof(Node) == kNodeBytes);
    std::vector<uint32_t> heads(size_t(width_) * size_t(height_));
    std::vector<Node> nodes(std::min<uint64_t>(stored_, pool_.capacity()));
    glGetNamedBufferSubData(lists_.heads.id(), 0, GLsizeiptr(heads.size() * 4), heads.data());
    glGetNamedBufferSubData(lists_.nodes.id(), 0, GLsizeiptr(nodes.size() * sizeof(Node)), nodes.data());
    std::vector<float> image(heads.size() * 4);
    std::vector<std::pair<uint64_t, uint32_t>> list;
    for (size_t pixel = 0; pixel < heads.size(); ++pixel) {
      list.clear();
      for (uint32_t cursor = heads[pixel]; cursor != 0xffffffffu && cursor < nodes.size(); cursor = nodes[cursor].next) {
        uint32_t bits = nodes[cursor].depth_bits;
        bits = (bits & 0x80000000u) ? ~bits : bits | 0x80000000u;  // float order as unsigned order
        list.push_back({(uint64_t(bits) << 32) | nodes[cursor].triangle_id, cursor});
      }
      std::sort(list.begin(), list.end());
      double accumulated[3] = {0.0, 0.0, 0.0}, transmittance = 1.0;
      for (const auto& [key, index] : list) {
        const float* c = nodes[index].color;
        const double weight = transmittance * double(c[3]);
        for (int k = 0; k < 3; ++k) accumulated[k] += weight * double(c[k]);
        transmittance *= 1.0 - double(c[3]);
      }
      for (int k = 0; k < 3; ++k) image[4 * pixel + k] = float(accumulated[k] + transmittance * double(frame.background[k]));
      image[4 * pixel + 3] = float(1.0 - transmittance);
    }
    if (cpu_result_width_ != width_ || cpu_result_height_ != height_) {
      cpu_result_ = make_texture_2d(GL_RGBA32F, width_, height_);
      cpu_result_framebuffer_ = make_framebuffer();
      glNamedFramebufferTexture(cpu_result_framebuffer_.id(), GL_COLOR_ATTACHMENT0, cpu_result_.id(), 0);
      cpu_result_width_ = width_;
      cpu_result_height_ = height_;
    }
    glTextureSubImage2D(cpu_result_.id(), 0, 0, 0, width_, height_, GL_RGBA, GL_FLOAT, image.data());
    glBlitNamedFramebuffer(cpu_result_framebuffer_.id(), frame.target_framebuffer, 0, 0, width_, height_, 0, 0,
                           width_, height_, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    gl_check("reference: CPU resolve of long lists");
  }

  // Resolve programs by local array size (powers of two from 16).
  const Program& resolve_program(uint32_t max_length) {
    const uint32_t size = std::max<uint32_t>(16, std::bit_ceil(std::max<uint32_t>(max_length, 1)));
    auto it = resolve_.find(size);
    if (it == resolve_.end()) {
      it = resolve_.emplace(size, build_fullscreen_program("algorithms/reference/resolve.frag",
                                                           {{"MAX_FRAGMENTS", std::to_string(size)}}))
               .first;
    }
    return it->second;
  }

  void allocate_pool(uint64_t capacity) {
    lists_.nodes = make_buffer(GLsizeiptr(capacity) * kNodeBytes);
    params_.values.capacity = GLuint(capacity);
  }

  int64_t nodes_per_pixel_;
  Program fill_;
  std::map<uint32_t, Program> resolve_;
  UniformBlock<ReferenceParams> params_{REFERENCE_PARAMS_BLOCK};
  PixelLists lists_;
  Framebuffer no_attachments_;
  Texture cpu_result_;  // only for frames resolved on the CPU
  Framebuffer cpu_result_framebuffer_;
  int cpu_result_width_ = 0, cpu_result_height_ = 0;
  int width_ = 0, height_ = 0;
  FragmentPool pool_;
  uint64_t stored_ = 0, passes_ = 0;
  uint32_t max_length_ = 0;
};

}  // namespace

void register_technique_reference(TechniqueRegistry& registry) {
  registry.add({
      .id = "reference",
      .display_name = "Exact reference (all fragments, double-precision blend)",
      .paper = "A-buffer (Carpenter 1984) as linked lists (Yang et al. 2010)",
      .params = {ParamSpec::integer("initial_nodes_per_pixel", 8, 1, 1024,
                                    "initial pool size per pixel; the pool grows on overflow")},
      .stages = {"clear", "fill", "compose"},
      .needs = {.fp64 = true},
      .exactness = Exactness::exact,
      .is_reference = true,
      .create = make_technique<Reference>,
      .storage_need = [](const ParamSet& params, const FrameContent& content) {
        const uint64_t nodes = fragment_pool::nodes_for(content, uint64_t(params.integer("initial_nodes_per_pixel")));
        return StorageNeed{nodes * kNodeBytes, content.pixels() * 8 + nodes * kNodeBytes};
      },
  });
}

}  // namespace oit
