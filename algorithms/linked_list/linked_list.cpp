// linked_list: per-pixel linked lists (Yang et al. 2010), the A-buffer of
// carnecky2013 / pastyrik2016. One geometry pass appends every fragment to
// its pixel's list; one full-screen pass gathers each list into a local
// array, sorts it by (view depth, stable triangle id) with the chosen sort,
// and composites it front to back in float. The node pool is sized from the
// previous frame's fragment count (growing with a re-render on overflow),
// from a counting pass, or to the worst case W*H*max_per_pixel
// (pool_sizing). With length_classes the resolve is drawn by 4x4 tiles
// classified by their longest list (length_classes.h), so short lists do not
// pay for the frame's longest one, and tiles of 0/1-fragment lists are not
// sorted at all.
#include <algorithm>
#include <bit>
#include <map>
#include <stdexcept>
#include <vector>

#include "harness/toolkit/fragment_pool.h"
#include "harness/toolkit/passes.h"
#include "harness/toolkit/pixel_lists.h"
#include "harness/toolkit/technique.h"
#include "harness/gl/check.h"
#include "harness/gl/shader_program.h"
#include "harness/gl/uniform_block.h"
#include "algorithms/linked_list/bindings.h"
#include "algorithms/linked_list/length_classes.h"
#include "algorithms/linked_list/sorting_network.h"

namespace oit {
namespace {

// LinkedListNode in nodes.glsl; storage=compact: three words (LL_COMPACT).
constexpr GLsizeiptr kNodeBytes = 32, kCompactNodeBytes = 12;
constexpr GLsizeiptr kCounterBytes = 12;  // node_count, max_length, dropped
// Interleaved lists per pixel (LL_HEADS, bindings.h).
constexpr GLsizeiptr kHeads = LL_HEADS;
// Per pixel: kHeads head pointers and the list length.
constexpr uint64_t kPixelBytes = 4 * kHeads + 4;
// Smallest local array compiled: tiny lists are not worth a program each.
constexpr uint32_t kSmallestArray = 8;
// Largest unrolled network (and its program); longer arrays fall back to the
// insertion sort, because a 256-element network is ~3000 compare-exchanges
// of straight-line code that takes llvmpipe far too long to compile.
constexpr uint32_t kLargestNetwork = 128;

using linked_list::kSorts;
using linked_list::Sort;

enum class PoolSizing { previous_frame, count, worst_case };
const Choices<PoolSizing> kPoolSizings{
    {PoolSizing::previous_frame, "previous_frame"}, {PoolSizing::count, "count"}, {PoolSizing::worst_case, "worst_case"}};
enum class Storage { full, compact };  // 32- or 12-byte nodes
const Choices<Storage> kStorages{{Storage::full, "full"}, {Storage::compact, "compact"}};

FragmentPool::Sizing pool_kind(PoolSizing sizing) {
  switch (sizing) {
    case PoolSizing::previous_frame: return FragmentPool::Sizing::previous_frame;
    case PoolSizing::count: return FragmentPool::Sizing::exact;
    case PoolSizing::worst_case: return FragmentPool::Sizing::fixed;
  }
  return FragmentPool::Sizing::fixed;
}

// The length classes (local array sizes) of a frame whose largest array is
// `array_size`: 1 (lists of 0 or 1 fragments, nothing to sort), the powers
// of two from kSmallestArray, then `array_size`.
std::vector<uint32_t> classes_for(uint32_t array_size) {
  std::vector<uint32_t> sizes = linked_list::class_sizes(std::min(kSmallestArray, array_size), array_size);
  if (sizes.front() > 1) sizes.insert(sizes.begin(), 1u);
  return sizes;
}

class LinkedList final : public Technique {
 public:
  explicit LinkedList(const ParamSet& params)
      : sort_(params.choice("sort", kSorts)),
        pool_sizing_(params.choice("pool_sizing", kPoolSizings)),
        // Only the network: the insertion and selection sorts loop as far as
        // the pixel's list, and measured slower drawn by class (README).
        length_classes_(params.boolean("length_classes") && sort_ == Sort::network),
        max_per_pixel_(uint32_t(params.integer("max_per_pixel"))),
        nodes_per_pixel_(uint64_t(params.integer("initial_nodes_per_pixel"))),
        compact_(params.choice("storage", kStorages) == Storage::compact),
        fill_(build_geometry_program("algorithms/linked_list/fill.frag", storage_defines())),
        lists_({LINKED_LIST_HEADS_BINDING, LINKED_LIST_NODES_BINDING, LINKED_LIST_COUNTERS_BINDING,
                LINKED_LIST_LENGTHS_BINDING},
               kCounterBytes),
        pool_("linked_list", pool_kind(pool_sizing_), node_bytes(), [this](uint64_t capacity) { allocate_pool(capacity); },
              1, compact_ ? 4 : 16) {
    params_.values.max_per_pixel = max_per_pixel_;
    if (pool_sizing_ == PoolSizing::count) {
      count_ = build_geometry_program("algorithms/linked_list/count.frag");
      count_query_ = make_query(GL_SAMPLES_PASSED);
    }
  }

  void resize(int width, int height) override {
    width_ = width;
    height_ = height;
    lists_.heads = make_buffer(GLsizeiptr(width) * height * 4 * kHeads);
    lists_.lengths = make_buffer(GLsizeiptr(width) * height * 4);
    heads_view_ = make_buffer_texture(lists_.heads, GL_RGBA32UI);  // a pixel's four heads in one texel
    lengths_view_ = make_buffer_texture(lists_.lengths, GL_R32UI);
    gl_check("creating the linked_list heads and lengths views");
    if (length_classes_) classes_.resize(width, height, classes_for(array_size_for(max_per_pixel_)).size());
    switch (pool_sizing_) {
      case PoolSizing::previous_frame: pool_.reset(uint64_t(width) * uint64_t(height) * nodes_per_pixel_); break;
      case PoolSizing::count: pool_.reset(1); break;  // the counting pass sizes it before every fill
      case PoolSizing::worst_case: pool_.reset(worst_case_nodes()); break;
    }
    dummy_framebuffer_ = make_attachmentless_framebuffer(width, height);
    params_.values.width = width;
  }

  void render(const Frame& frame) override {
    passes_ = 0;
    GLuint counts[3] = {0, 0, 0};  // node_count, max_length, dropped
    if (pool_sizing_ == PoolSizing::count) count_fragments(frame);
    // pool_sizing=count never overflows: the counting pass ran the same
    // geometry, so the fill produces exactly that count.
    passes_ += lists_.fill_until_fits(frame, pool_, [&] {
      params_.upload();  // the capacity may have grown since the last fill
      draw_scene_pass(frame, fill_, dummy_framebuffer_);
    }, counts);
    dropped_ = counts[2];
    stored_ = counts[0] - counts[2];

    auto compose = frame.clock.stage("compose");
    longest_ = counts[1];
    array_size_ = array_size_for(counts[1]);
    frame.bind_target();
    lists_.bind();
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glBindImageTexture(LINKED_LIST_NODES_IMAGE_UNIT, nodes_view_.id(), 0, GL_FALSE, 0, GL_READ_ONLY, node_format());
    glBindTextureUnit(LINKED_LIST_HEADS_UNIT, heads_view_.id());
    glBindTextureUnit(LINKED_LIST_LENGTHS_UNIT, lengths_view_.id());
    sizes_ = {array_size_};
    if (length_classes_) {
      // Each tile runs the smallest array (and network) that holds its
      // longest list. When every list is as long as the longest (fragments =
      // longest x pixels) there is one class, and one full-screen draw. A
      // frame whose array is the smallest (8) is drawn full screen too: the
      // classify pass and the point draws cost more than the network of 8
      // (19 compare-exchanges) that class 1 would save (README).
      const std::vector<uint32_t> classes = classes_for(array_size_);
      if (uint64_t(counts[0]) == uint64_t(counts[1]) * uint64_t(width_) * uint64_t(height_))
        sizes_ = {classes[linked_list::class_index(classes, longest_)]};
      else if (array_size_ > kSmallestArray)
        sizes_ = classes;
    }
    classes_.draw(frame, sizes_, [&](uint32_t size) { return program(Resolve::sorted, sort_for(size), size); });
    // Lists longer than max_per_pixel are left to a second draw that keeps
    // their nearest max_per_pixel fragments.
    if (dropped_ > 0) draw_fullscreen(frame, program(Resolve::truncated, sort_, max_per_pixel_));
    for (GLuint unit : {LINKED_LIST_HEADS_UNIT, LINKED_LIST_LENGTHS_UNIT}) glBindTextureUnit(unit, 0);
    glBindImageTexture(LINKED_LIST_NODES_IMAGE_UNIT, 0, 0, GL_FALSE, 0, GL_READ_ONLY, node_format());
  }

  TechniqueCounters counters() const override {
    TechniqueCounters c;
    c.bytes_allocated = uint64_t(width_) * uint64_t(height_) * kPixelBytes + pool_.capacity() * uint64_t(node_bytes()) +
                        kCounterBytes + (length_classes_ ? classes_.bytes_allocated() : 0);
    c.fragments_stored = stored_;
    c.fragments_dropped = dropped_;
    c.passes = passes_;
    c.overflow_retries = pool_.overflow_retries();
    work_saved(c);
    return c;
  }

 private:
  GLsizeiptr node_bytes() const { return compact_ ? kCompactNodeBytes : kNodeBytes; }
  // The resolve's image view of the nodes: words (compact) or 16-byte texels.
  GLenum node_format() const { return compact_ ? GL_R32UI : GL_RGBA32UI; }
  ShaderDefines storage_defines() const { return compact_ ? ShaderDefines{{"LL_COMPACT", "1"}} : ShaderDefines{}; }
  ShaderDefines with_storage(ShaderDefines defines) const {
    for (const auto& d : storage_defines()) defines.push_back(d);
    return defines;
  }

  uint64_t worst_case_nodes() const { return uint64_t(width_) * uint64_t(height_) * max_per_pixel_; }

  // pool_sizing=count: one geometry pass whose fragments the rasterizer
  // counts (GL_SAMPLES_PASSED on a single-sample framebuffer without depth
  // test or discard counts exactly the fill's fragments, under the same
  // scissor), with no shader work; then the pool is reallocated to exactly
  // that count (only when it changed).
  void count_fragments(const Frame& frame) {
    auto count = frame.clock.stage("count");
    glBeginQuery(GL_SAMPLES_PASSED, count_query_.id());
    draw_scene_pass(frame, count_, dummy_framebuffer_);
    glEndQuery(GL_SAMPLES_PASSED);
    ++passes_;
    GLuint fragments = 0;
    glGetQueryObjectuiv(count_query_.id(), GL_QUERY_RESULT, &fragments);
    pool_.set_exact(fragments);
  }

  // The sort a resolve of `array_size` elements runs: the network only up to
  // kLargestNetwork.
  Sort sort_for(uint32_t array_size) const {
    return (sort_ == Sort::network && array_size > kLargestNetwork) ? Sort::insertion : sort_;
  }

  // What pool_sizing and length_classes saved in the last frame against the
  // non-adaptive path (worst-case pool, one resolve at the frame's largest
  // array). Reads the per-pixel lengths back, outside the frame, and
  // classifies the tiles as classify.comp did.
  void work_saved(TechniqueCounters& c) const {
    const double bytes_not_allocated =
        pool_sizing_ == PoolSizing::worst_case ? 0.0 : (double(worst_case_nodes()) - double(pool_.capacity())) * double(node_bytes());
    c.work_saved.push_back({"bytes_not_allocated", bytes_not_allocated});
    const bool network = sort_ == Sort::network && array_size_ <= kLargestNetwork;
    uint64_t not_sorted = 0, short_groups = 0, exchanges_avoided = 0;
    if (length_classes_ && array_size_ > 0) {
      std::vector<uint32_t> lengths(size_t(width_) * size_t(height_));
      glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
      glGetNamedBufferSubData(lists_.lengths.id(), 0, GLsizeiptr(lengths.size() * 4), lengths.data());
      const std::vector<uint32_t> tile_longest = linked_list::tile_longest(lengths, width_, height_);
      const int tiles_x = (width_ + linked_list::LengthClasses::kTile - 1) / linked_list::LengthClasses::kTile;
      // Compare-exchanges of the network each array size runs (size 1: none).
      std::map<uint32_t, uint64_t> exchanges;
      for (uint32_t size : sizes_) exchanges[size] = linked_list::odd_even_merge_sort(size).size();
      const uint64_t full = linked_list::odd_even_merge_sort(array_size_).size();
      for (int y = 0; y < height_; ++y) {
        for (int x = 0; x < width_; ++x) {
          const uint32_t length = lengths[size_t(y) * size_t(width_) + size_t(x)];
          if (length > array_size_) continue;  // the truncating draw, the same in both paths
          const size_t tile = size_t(y / linked_list::LengthClasses::kTile) * size_t(tiles_x) +
                              size_t(x / linked_list::LengthClasses::kTile);
          const uint32_t size =
              sizes_.size() == 1 ? sizes_[0] : sizes_[linked_list::class_index(sizes_, tile_longest[tile])];
          if (length == 1 && size == 1) ++not_sorted;
          if (length >= 2 && size < array_size_) ++short_groups;
          exchanges_avoided += full - exchanges[size];
        }
      }
    }
    c.work_saved.push_back({"fragments_not_sorted", double(not_sorted)});
    c.work_saved.push_back({"pixels_in_short_groups", double(short_groups)});
    if (network) c.work_saved.push_back({"compare_exchanges_avoided", double(exchanges_avoided)});
  }

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

  // `kind` sorted (tile.vert + resolve.frag with `sort`, drawn by length
  // class or full screen) or truncated (resolve_truncated.frag, which ignores
  // `sort`), compiled once per local array size.
  enum class Resolve { sorted, truncated };
  GLuint program(Resolve kind, Sort sort, uint32_t array_size) {
    const std::string key = std::string(kind == Resolve::sorted ? "resolve" : "truncated") + ":" +
                            (kind == Resolve::sorted ? kSorts.name(sort) : "") + ":" + std::to_string(array_size);
    auto it = programs_.find(key);
    if (it == programs_.end()) {
      Program built =
          kind == Resolve::sorted
              ? build_program({{GL_VERTEX_SHADER, "algorithms/linked_list/tile.vert"},
                               {GL_FRAGMENT_SHADER, "algorithms/linked_list/resolve.frag"}},
                              with_storage(linked_list::tile_defines(linked_list::resolve_defines(sort, array_size))))
              : build_fullscreen_program("algorithms/linked_list/resolve_truncated.frag",
                                         with_storage({{"LL_CAPACITY", std::to_string(array_size)}}));
      it = programs_.emplace(key, std::move(built)).first;
    }
    return it->second.id();
  }

  void allocate_pool(uint64_t capacity) {
    lists_.nodes = make_buffer(GLsizeiptr(capacity) * node_bytes());
    nodes_view_ = make_buffer_texture(lists_.nodes, node_format());
    params_.values.capacity = GLuint(capacity);
  }

  Sort sort_;
  PoolSizing pool_sizing_;
  bool length_classes_;
  uint32_t max_per_pixel_;
  uint64_t nodes_per_pixel_;
  bool compact_;  // storage=compact: 12-byte nodes
  Program fill_, count_;
  UniformBlock<LinkedListParams> params_{LINKED_LIST_PARAMS_BLOCK};
  Query count_query_;  // pool_sizing=count's fragment count
  std::map<std::string, Program> programs_;  // by "kind:sort:array size"
  linked_list::LengthClasses classes_;         // tiles by list length (length_classes)
  std::vector<uint32_t> sizes_;                // the last frame's classes (one: a full-screen draw)
  PixelLists lists_;
  // The resolve reads the lists through buffer textures (the nodes as an
  // image of the same view): on llvmpipe a texelFetch or imageLoad with
  // per-pixel addresses is a vector gather, while an SSBO load with
  // per-pixel addresses is a lane-by-lane loop.
  Texture heads_view_, lengths_view_, nodes_view_;
  Framebuffer dummy_framebuffer_;
  int width_ = 0, height_ = 0;
  uint32_t longest_ = 0, array_size_ = 0;  // the last frame's longest list and largest local array
  FragmentPool pool_;
  uint64_t stored_ = 0, dropped_ = 0, passes_ = 0;
};

}  // namespace

void register_technique_linked_list(TechniqueRegistry& registry) {
  registry.add({
      .id = "linked_list",
      .display_name = "Per-pixel linked lists (A-buffer), float blend",
      .paper = "Yang et al. 2010; Carnecky et al. 2013; Pastyrik & Cmolik 2016",
      .params = {
          kSorts.spec("sort", Sort::network,
                      "resolve sort: insertion (Yang 2010), selection (Carnecky 2013) or an unrolled "
                      "odd-even merge sorting network on registers"),
          ParamSpec::integer("max_per_pixel", 64, 1, 1024,
                             "local array size; longer lists keep their nearest max_per_pixel fragments and count "
                             "the rest as dropped"),
          ParamSpec::integer("initial_nodes_per_pixel", 8, 1, 1024,
                             "first frame's pool per pixel with pool_sizing=previous_frame; later frames size it "
                             "from the last count"),
          kPoolSizings.spec("pool_sizing", PoolSizing::previous_frame,
                            "node pool: previous_frame (1.25 x the last frame's fragments, grown with a re-render "
                            "on overflow), count (a counting pass first, then exactly that many nodes; never "
                            "overflows) or worst_case (W x H x max_per_pixel nodes, allocated once)"),
          kStorages.spec("storage", Storage::full,
                         "node layout: full (32 bytes: float RGBA, view depth, triangle id, next; exact) or "
                         "compact (12 bytes: view depth, RGBA8 colour, next; colour quantised to 1/255 and "
                         "coplanar fragments ordered by allocation instead of triangle id)"),
          ParamSpec::boolean("length_classes", true,
                             "sort=network only: resolve each 4x4 tile with the smallest network that holds its "
                             "longest list: a compute pass classifies the tiles (1 = no sort, 8, 16, ... the frame's "
                             "array, when that is over 8) and each class is drawn as one point per tile; false: one "
                             "full-screen draw sorts every pixel in the array of the frame's longest list")},
      .stages = {"count", "clear", "fill", "compose"},
      // Every fragment is kept and exactly ordered (float blend) unless a list exceeds max_per_pixel.
      .exactness = Exactness::exact,
      .quality_sweep = {{"max_per_pixel", {"1", "2", "4", "8", "16", "32", "64"}},
                        {"sort", {"insertion", "network"}},
                        {"storage", {"compact", "full"}}},
      .adaptive_switches = {
          {"pool_count", "sizes the node pool exactly from a counting pass instead of W x H x max_per_pixel",
           {{"pool_sizing", "count"}}, {{"pool_sizing", "worst_case"}}},
          {"pool_previous_frame",
           "sizes the node pool from the previous frame's count instead of W x H x max_per_pixel",
           {{"pool_sizing", "previous_frame"}}, {{"pool_sizing", "worst_case"}}},
          {"length_classes", "sort=network: resolves each 4x4 tile with the smallest network that holds its longest "
           "list (no sort for 0/1-fragment tiles) instead of the frame's largest network everywhere",
           {{"length_classes", "true"}}, {{"length_classes", "false"}}}},
      // Yang et al. 2010 sort each list by insertion in a local array.
      .paper_preset = {{"sort", "insertion"}},
      .create = make_technique<LinkedList>,
      .storage_need = [](const ParamSet& params, const FrameContent& content) {
        const PoolSizing sizing = params.choice("pool_sizing", kPoolSizings);
        const uint64_t initial = uint64_t(params.integer("initial_nodes_per_pixel"));
        const uint64_t nodes =
            sizing == PoolSizing::count        ? std::max<uint64_t>(content.fragments, 1)
            : sizing == PoolSizing::worst_case ? content.pixels() * uint64_t(params.integer("max_per_pixel"))
                                               : fragment_pool::nodes_for(content, initial);
        const uint64_t node = params.choice("storage", kStorages) == Storage::compact ? kCompactNodeBytes : kNodeBytes;
        return StorageNeed{nodes * node, content.pixels() * (kPixelBytes + 2) + nodes * node};
      },
  });
}

}  // namespace oit
