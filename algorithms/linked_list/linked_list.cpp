// linked_list: per-pixel linked lists (Yang et al. 2010), the A-buffer of
// carnecky2013 / pastyrik2016. One geometry pass appends every fragment to
// its pixel's list; one full-screen pass gathers each list into a local
// array, sorts it by (view depth, stable triangle id) with the chosen sort,
// and composites it front to back in float. The node pool is sized from the
// previous frame's fragment count (growing with a re-render on overflow),
// from a counting pass, or to the worst case W*H*max_per_pixel
// (pool_sizing). With group_by_length the resolve is one draw per array
// size, so short lists do not pay for the frame's longest one, and lists of
// 0 or 1 fragments are not sorted at all.
#include <algorithm>
#include <bit>
#include <map>
#include <stdexcept>
#include <vector>

#include "core/technique.h"
#include "gl/check.h"
#include "gl/shader_program.h"
#include "sorting_network.h"
#include "../../shaders/bindings.h"

namespace oit {
namespace {

constexpr GLsizeiptr kNodeBytes = 32;     // LinkedListNode in nodes.glsl
constexpr GLsizeiptr kCounterBytes = 12;  // node_count, max_length, dropped
constexpr GLuint kHeadsBinding = OIT_FIRST_TECHNIQUE_BINDING + 0;
constexpr GLuint kNodesBinding = OIT_FIRST_TECHNIQUE_BINDING + 1;
constexpr GLuint kCountersBinding = OIT_FIRST_TECHNIQUE_BINDING + 2;
constexpr GLuint kLengthsBinding = OIT_FIRST_TECHNIQUE_BINDING + 3;
// Texture units of the resolve's read-only views (texelFetch of buffer textures).
constexpr GLuint kNodesUnit = 0, kHeadsUnit = 1, kLengthsUnit = 2;
constexpr GLint kCapacityLocation = OIT_FIRST_TECHNIQUE_UNIFORM + 0;
constexpr GLint kWidthLocation = OIT_FIRST_TECHNIQUE_UNIFORM + 1;
constexpr GLint kMaxPerPixelLocation = OIT_FIRST_TECHNIQUE_UNIFORM + 2;
constexpr GLint kMinLengthLocation = OIT_FIRST_TECHNIQUE_UNIFORM + 3;  // resolve.frag
// Smallest local array compiled: tiny lists are not worth a program each.
constexpr uint32_t kSmallestArray = 8;
// Largest unrolled network (and its program); longer arrays fall back to the
// insertion sort, because a 256-element network is ~3000 compare-exchanges
// of straight-line code that takes llvmpipe far too long to compile.
constexpr uint32_t kLargestNetwork = 128;
// The pool holds this much more than the fragments it was sized from.
constexpr double kPoolSlack = 1.25;

enum class PoolSizing { previous_frame, count, worst_case };

PoolSizing pool_sizing_from(const std::string& name) {
  if (name == "previous_frame") return PoolSizing::previous_frame;
  if (name == "count") return PoolSizing::count;
  if (name == "worst_case") return PoolSizing::worst_case;
  throw std::invalid_argument("linked_list: parameter 'pool_sizing' has no variant '" + name +
                              "'; choose previous_frame, count or worst_case");
}

// The local array sizes of the grouped resolve for a frame whose largest
// array is `largest`: powers of two from kSmallestArray, then `largest`.
std::vector<uint32_t> group_sizes(uint32_t largest) {
  std::vector<uint32_t> sizes;
  for (uint32_t size = kSmallestArray; size < largest; size *= 2) sizes.push_back(size);
  sizes.push_back(largest);
  return sizes;
}

class LinkedList final : public Technique {
 public:
  explicit LinkedList(const ParamSet& params)
      : sort_(params.choice("sort")),
        pool_sizing_(pool_sizing_from(params.choice("pool_sizing"))),
        group_by_length_(params.boolean("group_by_length")),
        max_per_pixel_(uint32_t(params.integer("max_per_pixel"))),
        nodes_per_pixel_(uint64_t(params.integer("initial_nodes_per_pixel"))),
        fill_(build_geometry_program("algorithms/linked_list/fill.frag")),
        counters_(make_buffer(kCounterBytes)) {
    linked_list::resolve_defines(sort_, 1);  // rejects an unknown sort before any frame
    glProgramUniform1ui(fill_.id(), kMaxPerPixelLocation, max_per_pixel_);
    if (pool_sizing_ == PoolSizing::count) count_ = build_geometry_program("algorithms/linked_list/count.frag");
  }

  void resize(int width, int height) override {
    width_ = width;
    height_ = height;
    heads_ = make_buffer(GLsizeiptr(width) * height * 4);
    lengths_ = make_buffer(GLsizeiptr(width) * height * 4);
    heads_view_ = buffer_view(heads_, GL_R32UI);
    lengths_view_ = buffer_view(lengths_, GL_R32UI);
    previous_fragments_ = 0;
    switch (pool_sizing_) {
      case PoolSizing::previous_frame: allocate_pool(uint64_t(width) * uint64_t(height) * nodes_per_pixel_); break;
      case PoolSizing::count: allocate_pool(1); break;  // the counting pass sizes it before every fill
      case PoolSizing::worst_case: allocate_pool(worst_case_nodes()); break;
    }
    dummy_framebuffer_ = make_framebuffer();
    glNamedFramebufferParameteri(dummy_framebuffer_.id(), GL_FRAMEBUFFER_DEFAULT_WIDTH, width);
    glNamedFramebufferParameteri(dummy_framebuffer_.id(), GL_FRAMEBUFFER_DEFAULT_HEIGHT, height);
    glProgramUniform1i(fill_.id(), kWidthLocation, width_);
    for (auto& [key, program] : programs_) glProgramUniform1i(program.id(), kWidthLocation, width_);
  }

  void render(const Frame& frame) override {
    passes_ = 0;
    GLuint counts[3] = {0, 0, 0};  // node_count, max_length, dropped
    if (pool_sizing_ == PoolSizing::count) count_fragments(frame);
    for (;;) {
      {
        auto clear = frame.clock.stage("clear");
        // A pool far larger than the last frame needed shrinks to that need
        // (with slack); the factor 2 keeps it from reallocating every frame.
        const uint64_t wanted = pool_size_for(previous_fragments_);
        if (pool_sizing_ == PoolSizing::previous_frame && previous_fragments_ > 0 && capacity_ > 2 * wanted)
          allocate_pool(wanted);
        const GLuint nil = 0xffffffffu, zero = 0;
        glClearNamedBufferData(heads_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &nil);
        glClearNamedBufferData(lengths_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
        glClearNamedBufferData(counters_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
      }
      {
        auto fill = frame.clock.stage("fill");
        glBindFramebuffer(GL_FRAMEBUFFER, dummy_framebuffer_.id());
        glViewport(0, 0, width_, height_);
        glUseProgram(fill_.id());
        frame.set_shared_uniforms(fill_.id());
        bind_storage();
        frame.scene.draw();
        ++passes_;
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        glGetNamedBufferSubData(counters_.id(), 0, sizeof(counts), counts);
      }
      previous_fragments_ = counts[0];
      if (counts[0] <= capacity_) break;
      // Overflow: nothing is dropped silently; grow to this view's need and
      // render again. pool_sizing=count never gets here: the counting pass
      // ran the same geometry, so the fill produces exactly that count.
      ++overflow_retries_;
      allocate_pool(pool_sizing_ == PoolSizing::count ? counts[0] : pool_size_for(counts[0]));
    }
    dropped_ = counts[2];
    stored_ = counts[0] - counts[2];

    auto compose = frame.clock.stage("compose");
    longest_ = counts[1];
    array_size_ = array_size_for(counts[1]);
    frame.bind_target();
    bind_storage();
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    glBindTextureUnit(kNodesUnit, nodes_view_.id());
    glBindTextureUnit(kHeadsUnit, heads_view_.id());
    glBindTextureUnit(kLengthsUnit, lengths_view_.id());
    if (!group_by_length_) {
      draw_resolve(frame, array_size_, 0);
    } else {
      // Every pixel is drawn by exactly one of these: lists of 0 or 1
      // fragments without a sort, then each list by the smallest array that
      // holds it. A draw of lengths the frame does not have is not issued.
      draw_fullscreen(frame, program("short", "", 1));
      uint32_t shortest = 2;
      for (uint32_t size : group_sizes(array_size_)) {
        if (shortest <= size && shortest <= longest_) draw_resolve(frame, size, shortest);
        shortest = size + 1;
      }
    }
    // Lists longer than max_per_pixel are left to a second draw that keeps
    // their nearest max_per_pixel fragments.
    if (dropped_ > 0) draw_fullscreen(frame, program("truncated", "", max_per_pixel_));
    for (GLuint unit : {kNodesUnit, kHeadsUnit, kLengthsUnit}) glBindTextureUnit(unit, 0);
  }

  TechniqueCounters counters() const override {
    TechniqueCounters c;
    c.bytes_allocated = uint64_t(width_) * uint64_t(height_) * 8 + capacity_ * uint64_t(kNodeBytes) + kCounterBytes;
    c.fragments_stored = stored_;
    c.fragments_dropped = dropped_;
    c.passes = passes_;
    c.overflow_retries = overflow_retries_;
    work_saved(c);
    return c;
  }

 private:
  uint64_t worst_case_nodes() const { return uint64_t(width_) * uint64_t(height_) * max_per_pixel_; }

  // pool_sizing=count: one geometry pass that only counts fragments, then
  // the pool is reallocated to exactly that count (only when it changed).
  void count_fragments(const Frame& frame) {
    auto count = frame.clock.stage("count");
    const GLuint zero = 0;
    glClearNamedBufferData(counters_.id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glBindFramebuffer(GL_FRAMEBUFFER, dummy_framebuffer_.id());
    glViewport(0, 0, width_, height_);
    glUseProgram(count_.id());
    frame.set_shared_uniforms(count_.id());
    bind_storage();
    frame.scene.draw();
    ++passes_;
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint fragments = 0;
    glGetNamedBufferSubData(counters_.id(), 0, sizeof fragments, &fragments);
    if (std::max<uint64_t>(fragments, 1) != capacity_) allocate_pool(fragments);
  }

  // One resolve draw of the lists with min_length .. array_size fragments.
  void draw_resolve(const Frame& frame, uint32_t array_size, uint32_t min_length) {
    const std::string sort = (sort_ == "network" && array_size > kLargestNetwork) ? "insertion" : sort_;
    const GLuint resolve = program("resolve", sort, array_size);
    glProgramUniform1ui(resolve, kMinLengthLocation, min_length);
    draw_fullscreen(frame, resolve);
  }

  // What pool_sizing and group_by_length saved in the last frame against
  // the non-adaptive path (worst-case pool, one resolve at the frame's
  // largest array). Reads the per-pixel lengths back, outside the frame.
  void work_saved(TechniqueCounters& c) const {
    const double bytes_not_allocated =
        pool_sizing_ == PoolSizing::worst_case ? 0.0 : (double(worst_case_nodes()) - double(capacity_)) * kNodeBytes;
    c.work_saved.push_back({"bytes_not_allocated", bytes_not_allocated});
    const bool network = sort_ == "network" && array_size_ <= kLargestNetwork;
    uint64_t not_sorted = 0, short_groups = 0, exchanges_avoided = 0;
    if (group_by_length_ && array_size_ > 0) {
      std::vector<uint32_t> lengths(size_t(width_) * size_t(height_));
      glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
      glGetNamedBufferSubData(lengths_.id(), 0, GLsizeiptr(lengths.size() * 4), lengths.data());
      // Compare-exchanges of the network each array size runs (0: no sort).
      const std::vector<uint32_t> sizes = group_sizes(array_size_);
      std::map<uint32_t, uint64_t> exchanges = {{0u, 0u}};
      for (uint32_t size : sizes) exchanges[size] = linked_list::odd_even_merge_sort(size).size();
      for (uint32_t length : lengths) {
        if (length > array_size_) continue;  // the truncating draw, the same in both paths
        const uint32_t size = length <= 1 ? 0u : *std::lower_bound(sizes.begin(), sizes.end(), length);
        if (length == 1) ++not_sorted;
        if (length >= 2 && size < array_size_) ++short_groups;
        exchanges_avoided += exchanges[array_size_] - exchanges[size];
      }
    }
    c.work_saved.push_back({"fragments_not_sorted", double(not_sorted)});
    c.work_saved.push_back({"pixels_in_short_groups", double(short_groups)});
    if (network) c.work_saved.push_back({"compare_exchanges_avoided", double(exchanges_avoided)});
  }

  static uint64_t pool_size_for(uint64_t fragments) { return uint64_t(double(fragments) * kPoolSlack) + 1; }

  // Local array for the frame's longest list: a power of two (so a few
  // programs serve every frame), never more than max_per_pixel.
  uint32_t array_size_for(uint32_t longest_list) const {
    const uint32_t needed = std::max(kSmallestArray, std::bit_ceil(std::max<uint32_t>(longest_list, 1)));
    return std::min(needed, max_per_pixel_);
  }

  static void draw_fullscreen(const Frame& frame, GLuint program) {
    glUseProgram(program);
    frame.set_shared_uniforms(program);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }

  // `kind` "resolve" (resolve.frag with `sort`), "truncated"
  // (resolve_truncated.frag) or "short" (resolve_short.frag), compiled once
  // per local array size.
  GLuint program(const std::string& kind, const std::string& sort, uint32_t array_size) {
    const std::string key = kind + ":" + sort + ":" + std::to_string(array_size);
    auto it = programs_.find(key);
    if (it == programs_.end()) {
      Program built = kind == "resolve"     ? build_fullscreen_program("algorithms/linked_list/resolve.frag",
                                                                       linked_list::resolve_defines(sort, array_size))
                      : kind == "short"     ? build_fullscreen_program("algorithms/linked_list/resolve_short.frag")
                                            : build_fullscreen_program("algorithms/linked_list/resolve_truncated.frag",
                                                                       {{"LL_CAPACITY", std::to_string(array_size)}});
      it = programs_.emplace(key, std::move(built)).first;
      glProgramUniform1i(it->second.id(), kWidthLocation, width_);
    }
    return it->second.id();
  }

  void allocate_pool(uint64_t capacity) {
    capacity = std::max<uint64_t>(capacity, 1);
    GLint64 max_block = 0, max_texels = 0;
    glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
    glGetInteger64v(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
    const GLint64 node_texels = GLint64(kNodeBytes / 16);
    if (capacity > 0x7ffffffeull / uint64_t(node_texels) ||
        (max_block > 0 && GLint64(capacity) * kNodeBytes > max_block) ||
        (max_texels > 0 && GLint64(capacity) * node_texels > max_texels)) {
      throw std::runtime_error("linked_list: a pool of " + std::to_string(capacity) + " fragments (" +
                               std::to_string(capacity * kNodeBytes >> 20) +
                               " MiB) exceeds the device's largest storage buffer (" +
                               std::to_string(max_block >> 20) + " MiB) or buffer texture (" +
                               std::to_string(max_texels) + " texels); render at a smaller size");
    }
    nodes_ = make_buffer(GLsizeiptr(capacity) * kNodeBytes);
    nodes_view_ = buffer_view(nodes_, GL_RGBA32UI);
    gl_check("allocating the linked_list node pool");
    capacity_ = capacity;
    glProgramUniform1ui(fill_.id(), kCapacityLocation, GLuint(capacity_));
  }

  // The resolve reads the lists through buffer textures: on llvmpipe a
  // texelFetch with per-pixel addresses is a vector gather, while an SSBO
  // load with per-pixel addresses is a lane-by-lane loop.
  static Texture buffer_view(const Buffer& buffer, GLenum format) {
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_BUFFER, 1, &id);
    Texture view(id);
    glTextureBuffer(view.id(), format, buffer.id());
    gl_check("creating a linked_list buffer texture");
    return view;
  }

  void bind_storage() const {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kHeadsBinding, heads_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kNodesBinding, nodes_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kCountersBinding, counters_.id());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, kLengthsBinding, lengths_.id());
  }

  std::string sort_;
  PoolSizing pool_sizing_;
  bool group_by_length_;
  uint32_t max_per_pixel_;
  uint64_t nodes_per_pixel_;
  Program fill_, count_;
  std::map<std::string, Program> programs_;  // by "kind:sort:array size"
  Buffer counters_, heads_, lengths_, nodes_;
  Texture heads_view_, lengths_view_, nodes_view_;
  Framebuffer dummy_framebuffer_;
  int width_ = 0, height_ = 0;
  uint32_t longest_ = 0, array_size_ = 0;  // the last frame's longest list and largest local array
  uint64_t capacity_ = 0, previous_fragments_ = 0, stored_ = 0, dropped_ = 0, passes_ = 0, overflow_retries_ = 0;
};

}  // namespace

void register_technique_linked_list(TechniqueRegistry& registry) {
  TechniqueDescriptor d;
  d.id = "linked_list";
  d.display_name = "Per-pixel linked lists (A-buffer), float blend";
  d.paper = "Yang et al. 2010; Carnecky et al. 2013; Pastyrik & Kolingerova 2016";
  d.params = {
      ParamSpec::choice("sort", "network", {"insertion", "selection", "network"},
                        "resolve sort: insertion (Yang 2010), selection (Carnecky 2013) or an unrolled "
                        "odd-even merge sorting network on registers"),
      ParamSpec::integer("max_per_pixel", 64, 1, 1024,
                         "local array size; longer lists keep their nearest max_per_pixel fragments and count "
                         "the rest as dropped"),
      ParamSpec::integer("initial_nodes_per_pixel", 8, 1, 1024,
                         "first frame's pool per pixel with pool_sizing=previous_frame; later frames size it "
                         "from the last count"),
      ParamSpec::choice("pool_sizing", "previous_frame", {"previous_frame", "count", "worst_case"},
                        "node pool: previous_frame (1.25 x the last frame's fragments, grown with a re-render "
                        "on overflow), count (a counting pass first, then exactly that many nodes; never "
                        "overflows) or worst_case (W x H x max_per_pixel nodes, allocated once)"),
      ParamSpec::boolean("group_by_length", false,
                         "resolve lists of 0 or 1 fragments without sorting and every other list with the "
                         "smallest power-of-two array that holds it (one draw per size); false: one draw "
                         "sorts every pixel in the array of the frame's longest list")};
  d.stages = {"count", "clear", "fill", "compose"};
  // Every fragment is kept and exactly ordered (float blend) unless a list exceeds max_per_pixel.
  d.exactness = Exactness::exact;
  d.quality_sweep = {{"max_per_pixel", {"1", "2", "4", "8", "16", "32", "64"}}, {"sort", {"insertion", "network"}}};
  d.adaptive_switches = {
      {"pool_count", "sizes the node pool exactly from a counting pass instead of W x H x max_per_pixel",
       {{"pool_sizing", "count"}}, {{"pool_sizing", "worst_case"}}},
      {"pool_previous_frame", "sizes the node pool from the previous frame's count instead of W x H x max_per_pixel",
       {{"pool_sizing", "previous_frame"}}, {{"pool_sizing", "worst_case"}}},
      {"group_by_length", "skips the sort of 0/1-fragment lists and sorts each list in the smallest array that holds it",
       {{"group_by_length", "true"}}, {{"group_by_length", "false"}}}};
  d.create = [](const ParamSet& params) { return std::make_unique<LinkedList>(params); };
  registry.add(std::move(d));
}

}  // namespace oit
