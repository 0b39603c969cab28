// linearized_fragment_buffer: the l-LFB of Knowles et al. 2012, exact. A
// counting pass (additive blending, harness/toolkit/list_length_pass.h) gives every
// pixel's fragment count; a prefix sum in compute turns the counts into
// offsets, so each pixel owns one contiguous range of a pool of exactly the
// frame's fragments; the fill writes every fragment at its pixel's offset +
// an atomic increment of the pixel's own cursor (no global counter); the
// resolve reads each range in order, sorts it in registers (linked_list's
// odd-even merge network, or register-based block sort, Knowles et al.
// 2014) and blends front to back in float. The resolve is drawn by length
// class (backwards memory allocation, Knowles et al. 2013, with linked_list's
// 4x4 tile classes) so that short lists do not pay for the longest.
#include <algorithm>
#include <bit>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "algorithms/linked_list/length_classes.h"
#include "algorithms/linked_list/sorting_network.h"
#include "harness/toolkit/fragment_pool.h"
#include "harness/toolkit/list_length_pass.h"
#include "harness/toolkit/passes.h"
#include "harness/toolkit/technique.h"
#include "harness/gl/check.h"
#include "harness/gl/shader_program.h"
#include "harness/gl/uniform_block.h"
#include "algorithms/linearized_fragment_buffer/bindings.h"
#include "algorithms/linearized_fragment_buffer/prefix_sum.h"

namespace oit {
namespace {

// Per fragment one 24-byte node (storage.glsl): the key (view depth in
// unsigned order, triangle id) and the RGBA32F colour, read as RG32UI texels;
// on unlit scenes with flat_color_nodes, the 8-byte key alone (the colour is
// the triangle's, fetched by its id from the scene's flat-colour table).
constexpr uint64_t kNodeBytes = 24, kFlatNodeBytes = 8, kTexelBytes = 8;
// Per pixel: the R32F count, the offset, the length and the fill cursor (a
// buffer, or the R32UI target with fill=framebuffer_fetch); the offsets
// have one more value (the total).
constexpr uint64_t kPixelBytes = 16;
// The smallest array compiled, as in linked_list: tiny lists are not worth a program each.
constexpr uint32_t kSmallestArray = 8;
// The largest whole-list network; longer arrays are sorted in register
// blocks (llvmpipe compiles a 256-element network for minutes).
constexpr uint32_t kLargestNetwork = 128;

enum class Sort { network, register_block };
const Choices<Sort> kSorts{{Sort::network, "network"}, {Sort::register_block, "register_block"}};
const Choices<uint32_t> kBlockSizes{{8, "8"}, {16, "16"}, {32, "32"}};
// How a fragment finds its slot (README: fill): an atomic increment of the
// pixel's cursor in an image, or the cursor as the pixel's R32UI colour,
// read and written in primitive order through framebuffer fetch.
// Where the counts become offsets (README: scan).
enum class Scan { automatic, compute, host };
const Choices<Scan> kScans{{Scan::automatic, "auto"}, {Scan::compute, "compute"}, {Scan::host, "host"}};
// How a flat node's 8-byte key is written and compared (README: key_format).
enum class KeyFormat { automatic, uint64, uint32_pair };
const Choices<KeyFormat> kKeyFormats{
    {KeyFormat::automatic, "auto"}, {KeyFormat::uint64, "uint64"}, {KeyFormat::uint32_pair, "uint32_pair"}};

constexpr const char* kFillShader = "algorithms/linearized_fragment_buffer/fill.frag";

// The explicit choice this device cannot run, or "": the harness skips
// such a run (extra_support_check).
std::string missing_device_feature(const ParamSet& params, const DeviceProfile& device) {
  if (std::string missing = missing_slot_fill_feature(params.choice("fill", kSlotFills), device); !missing.empty())
    return missing;
  if (params.choice("key_format", kKeyFormats) == KeyFormat::uint64 && !device.int64)
    return "key_format=uint64 needs GL_ARB_gpu_shader_int64, which this device lacks (use key_format=uint32_pair or "
           "auto)";
  return "";
}

// The resolution rule. fill=auto: framebuffer fetch where the device has
// it. key_format=auto: one uint64 where the device has 64-bit integers.
// scan=auto: on the host where the "GPU" is the CPU (the counts are read
// back for the pool size anyway, and a running sum there costs less than the
// compute dispatches; README: scan), in compute shaders on a GPU.
RawParams resolve_parameters(const ParamSet& requested, const ResolveInput& input) {
  RawParams resolved;
  resolved["fill"] = kSlotFills.name(resolve_slot_fill(requested.choice("fill", kSlotFills), input.device));
  if (requested.choice("key_format", kKeyFormats) == KeyFormat::automatic)
    resolved["key_format"] = input.device.int64 ? "uint64" : "uint32_pair";
  if (requested.choice("scan", kScans) == Scan::automatic) resolved["scan"] = input.device.software ? "host" : "compute";
  return resolved;
}

// A parameter the resolution rule leaves concrete; throws for an unresolved auto.
template <typename E>
E resolved(const ParamSet& params, const std::string& name, const Choices<E>& table) {
  const E value = params.choice(name, table);
  if (params.choice(name) == "auto")
    throw std::logic_error("linearized_fragment_buffer: " + name + "=auto reached the technique unresolved");
  return value;
}

// The resolve's #defines for an array of `size` fragments: one network of
// `size`, or blocks of `block` sorted by its network and merged; the final
// cursors it checks in the fill's R32UI target (fetch) or cursor buffer.
ShaderDefines resolve_defines(uint32_t size, bool blocks, uint32_t block, bool flat, bool key64, bool fetch) {
  ShaderDefines defines = linked_list::resolve_defines(linked_list::Sort::network, blocks ? block : size);
  if (flat) defines.push_back({"LFB_FLAT_COLOR", "1"});
  if (fetch) defines.push_back({"LFB_FETCH_CURSOR", "1"});
  if (flat && key64) defines.push_back({"LFB_KEY64", "1"});
  if (!blocks) {
    defines.push_back({"LFB_NETWORK", "1"});
    return defines;
  }
  const uint32_t count = (size + block - 1) / block;
  defines.push_back({"LFB_BLOCKS", std::to_string(count)});
  defines.push_back({"LFB_FETCH_ALL", linked_list::macro_sequence("LFB_FETCH", block)});
  defines.push_back({"LFB_STORE_ALL", linked_list::macro_sequence("LFB_STORE", block)});
  defines.push_back({"LFB_HEAD_ALL", linked_list::macro_sequence("LFB_HEAD", count)});
  defines.push_back({"LFB_PICK_ALL", linked_list::macro_sequence("LFB_PICK", count)});
  defines.push_back({"LFB_ADVANCE_ALL", linked_list::macro_sequence("LFB_ADVANCE", count)});
  return defines;
}

class LinearizedFragmentBuffer final : public Technique {
 public:
  explicit LinearizedFragmentBuffer(const ParamSet& params)
      : register_blocks_(params.choice("sort", kSorts) == Sort::register_block),
        block_(params.choice("block_size", kBlockSizes)),
        backwards_allocation_(params.boolean("backwards_allocation")),
        flat_color_nodes_(params.boolean("flat_color_nodes")),
        host_scan_(resolved(params, "scan", kScans) == Scan::host),
        key64_(resolved(params, "key_format", kKeyFormats) == KeyFormat::uint64),
        cursors_(params.choice("fill", kSlotFills)),
        fill_(build_geometry_program(kFillShader, fill_defines(false))),
        mismatched_(make_buffer(4)),
        pool_("linearized_fragment_buffer", FragmentPool::Sizing::exact, kNodeBytes,
              [this](uint64_t capacity) { allocate_pool(capacity); }, 1, kTexelBytes) {}

  void resize(int width, int height) override {
    width_ = width;
    height_ = height;
    const uint64_t pixels = uint64_t(width) * uint64_t(height);
    list_lengths_.resize(width, height);
    prefix_sum_.resize(pixels);
    offsets_ = make_buffer(GLsizeiptr((pixels + 1) * 4));
    lengths_ = make_buffer(GLsizeiptr(pixels * 4));
    host_lengths_.resize(pixels);
    offsets_view_ = make_buffer_texture(offsets_, GL_R32UI);
    lengths_view_ = make_buffer_texture(lengths_, GL_R32UI);
    cursors_.resize(width, height, "linearized_fragment_buffer");
    class_capacity_ = 0;
    pool_.reset(1);  // the prefix sum sizes it before every fill
    params_.values.width = width;
    gl_check("allocating the linearized fragment buffer's per-pixel storage");
  }

  void render(const Frame& frame) override {
    {
      // The counting pass and the prefix sum: everything that sizes the frame.
      auto count = frame.clock.stage("count");
      // Its nodes keep no light factor: unlit scenes only.
      flat_ = flat_color_nodes_ && frame.scene.shading() == SceneShading::unlit && frame.scene.flat_colors_view() != 0;
      pool_.set_record_bytes(node_bytes());
      if (host_scan_) scan_on_host(frame);
      else scan_on_device(frame);
      glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT);  // the copy below reads the scan's writes
      pool_.before_fill(frame);
      pool_.set_exact(fragments_);
      cursors_.start(offsets_);
      fill_buffer_u32(mismatched_, 0);
    }
    params_.upload();
    fill(frame);
    auto compose = frame.clock.stage("compose");
    frame.bind_target();
    // Read-write: register blocks write their sorted blocks back.
    glBindImageTexture(LFB_NODES_IMAGE_UNIT, nodes_view_.id(), 0, GL_FALSE, 0, GL_READ_WRITE, GL_RG32UI);
    SlotCursors::unbind_image(LFB_CURSORS_IMAGE_UNIT);
    glBindTextureUnit(LFB_OFFSETS_UNIT, offsets_view_.id());
    glBindTextureUnit(LFB_LENGTHS_UNIT, lengths_view_.id());
    glBindTextureUnit(LFB_FINAL_CURSORS_UNIT, cursors_.final_cursors());
    bind_storage_buffers({{LFB_MISMATCHED_BINDING, &mismatched_}});
    if (flat_) glBindTextureUnit(LFB_FLAT_COLORS_UNIT, frame.scene.flat_colors_view());
    const std::vector<uint32_t> sizes = class_sizes();
    if (sizes.size() > class_capacity_) {
      class_capacity_ = sizes.size();
      classes_.resize(width_, height_, class_capacity_);
    }
    classes_.draw(frame, sizes, [&](uint32_t size) { return program(size); });
    for (GLuint unit : {LFB_OFFSETS_UNIT, LFB_LENGTHS_UNIT, LFB_FLAT_COLORS_UNIT, LFB_FINAL_CURSORS_UNIT})
      glBindTextureUnit(unit, 0);
    glBindImageTexture(LFB_NODES_IMAGE_UNIT, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RG32UI);
    check_ranges();
  }

  TechniqueCounters counters() const override {
    TechniqueCounters c;
    const uint64_t pixels = uint64_t(width_) * uint64_t(height_);
    c.bytes_allocated = pixels * kPixelBytes + 4 + prefix_sum_.bytes_allocated() +
                        pool_.capacity() * node_bytes() +
                        4 + (class_capacity_ > 0 ? classes_.bytes_allocated() : 0) + flat_table_bytes_;
    c.extra.push_back({"node_bytes", double(node_bytes())});
    // Which paths fill=auto and scan=auto took on this device.
    c.extra.push_back({"framebuffer_fetch_fill", cursors_.by_framebuffer_fetch() ? 1.0 : 0.0});
    c.extra.push_back({"host_scan", host_scan_ ? 1.0 : 0.0});
    c.extra.push_back({"uint64_keys", flat_ && key64_ ? 1.0 : 0.0});
    c.fragments_stored = fragments_;
    c.passes = 2;
    c.overflow_retries = pool_.overflow_retries();
    return c;
  }

 private:
  ShaderDefines fill_defines(bool flat) const {
    ShaderDefines defines;
    if (flat) defines.push_back({"LFB_FLAT_COLOR", "1"});
    if (cursors_.by_framebuffer_fetch()) defines.push_back({"LFB_FETCH_CURSOR", "1"});
    if (flat && key64_) defines.push_back({"LFB_KEY64", "1"});
    return defines;
  }

  void fill(const Frame& frame) {
    auto fill = frame.clock.stage("fill");
    glBindImageTexture(LFB_NODES_IMAGE_UNIT, nodes_view_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32UI);
    if (flat_ && key64_) bind_storage_buffers({{LFB_KEYS_BINDING, &nodes_}});
    cursors_.bind_image(LFB_CURSORS_IMAGE_UNIT);
    if (flat_ && fill_flat_.id() == 0) {
      fill_flat_ = build_geometry_program(kFillShader, fill_defines(true));
    }
    flat_table_bytes_ = flat_ ? frame.scene.flat_colors_bytes() : 0;
    draw_scene_pass(frame, flat_ ? fill_flat_ : fill_, cursors_.fill_framebuffer());
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  }

  // The counts read back, then the lengths the resolve and the length
  // classes read and the offsets, from the host (whole numbers in float).
  void scan_on_host(const Frame& frame) {
    longest_ = list_lengths_.longest_list(frame);
    fragments_ = list_lengths_.total_fragments();
    prefix_sum_.scan_host_counts(list_lengths_.host_counts(), offsets_);
    lengths_from_counts(list_lengths_.host_counts(), host_lengths_);
    glNamedBufferSubData(lengths_.id(), 0, GLsizeiptr(host_lengths_.size() * 4), host_lengths_.data());
  }

  // The counts stay on the device: the scan writes offsets and lengths and
  // the host reads back two words (the total and the longest list); on a
  // GPU reading the whole count target back took most of the stage.
  void scan_on_device(const Frame& frame) {
    list_lengths_.draw(frame);
    prefix_sum_.scan_counts(list_lengths_.counts(), width_, offsets_, lengths_);
    const lfb::PrefixSum::Summary summary = prefix_sum_.read_summary(offsets_);
    longest_ = summary.longest;
    fragments_ = summary.total;
    // The 32-bit offsets wrap past 2^32 fragments: where that is possible,
    // sum the counts on the host, which fails with a clear error.
    if (uint64_t(longest_) * uint64_t(width_) * uint64_t(height_) > UINT32_MAX) {
      list_lengths_.read_back();
      std::vector<uint32_t> offsets;
      offsets_from_counts(list_lengths_.host_counts(), offsets);
    }
  }

  // The resolve counted the pixels whose fill outgrew (or fell short of)
  // their counted range (resolve.frag, check_range): the image is wrong.
  void check_ranges() const {
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint mismatched = 0;
    glGetNamedBufferSubData(mismatched_.id(), 0, 4, &mismatched);
    fail_on_mismatched_ranges("linearized_fragment_buffer", mismatched, fragments_);
  }

  // The length classes of this frame (backwards memory allocation): one
  // array for the frame's longest list, or that and the powers of two below
  // it from kSmallestArray, plus 1 (0/1-fragment tiles, no sort). As in
  // linked_list: one class when every list is as long as the longest, or
  // when the longest is short.
  std::vector<uint32_t> class_sizes() const {
    const uint32_t array = std::max(kSmallestArray, std::bit_ceil(std::max<uint32_t>(longest_, 1)));
    const bool uniform = fragments_ == uint64_t(longest_) * uint64_t(width_) * uint64_t(height_);
    if (!backwards_allocation_ || array == kSmallestArray || uniform) return {uniform ? std::max(longest_, 1u) : array};
    std::vector<uint32_t> sizes = linked_list::class_sizes(kSmallestArray, array);
    sizes.insert(sizes.begin(), 1u);
    return sizes;
  }

  // The resolve for an array of `size`: the whole-list network, or register
  // blocks when sort=register_block and the array is larger than a block, or
  // when the array is larger than the largest network.
  GLuint program(uint32_t size) {
    auto it = programs_.find({size, flat_});
    if (it == programs_.end()) {
      const bool blocks = size > block_ && (register_blocks_ || size > kLargestNetwork);
      Program built = build_program({{GL_VERTEX_SHADER, "algorithms/linked_list/tile.vert"},
                                     {GL_FRAGMENT_SHADER, "algorithms/linearized_fragment_buffer/resolve.frag"}},
                                    linked_list::tile_defines(
                                        resolve_defines(size, blocks, block_, flat_, key64_, cursors_.by_framebuffer_fetch())));
      it = programs_.emplace(std::make_pair(size, flat_), std::move(built)).first;
    }
    return it->second.id();
  }

  uint64_t node_bytes() const { return flat_ ? kFlatNodeBytes : kNodeBytes; }

  void allocate_pool(uint64_t capacity) {
    nodes_ = make_buffer(GLsizeiptr(capacity * node_bytes()));
    nodes_view_ = make_buffer_texture(nodes_, GL_RG32UI);
  }

  bool register_blocks_;
  uint32_t block_;
  bool backwards_allocation_, flat_color_nodes_, host_scan_, key64_;
  SlotCursors cursors_;  // before fill_: fill_defines() asks it how the fill takes its slots
  bool flat_ = false;  // this frame stores flat-colour nodes
  uint64_t flat_table_bytes_ = 0;
  Program fill_, fill_flat_;
  UniformBlock<LfbParams> params_{LFB_PARAMS_BLOCK};
  ListLengthPass list_lengths_;
  lfb::PrefixSum prefix_sum_;
  linked_list::LengthClasses classes_;
  size_t class_capacity_ = 0;
  std::map<std::pair<uint32_t, bool>, Program> programs_;  // resolves by (array size, flat colours)
  Buffer offsets_, lengths_, mismatched_, nodes_;
  Texture offsets_view_, lengths_view_, nodes_view_;
  std::vector<uint32_t> host_lengths_;
  int width_ = 0, height_ = 0;
  uint32_t longest_ = 0;
  uint64_t fragments_ = 0;
  FragmentPool pool_;
};

}  // namespace

void register_technique_linearized_fragment_buffer(TechniqueRegistry& registry) {
  registry.add({
      .id = "linearized_fragment_buffer",
      .display_name = "Linearized fragment buffer (l-LFB), float blend",
      .paper =
          "Knowles et al. 2012; register-based block sort and backwards memory allocation: Knowles et al. 2013, 2014",
      .params = {
          kSorts.spec("sort", Sort::network,
                      "network: the whole list in registers, sorted by an unrolled odd-even merge network "
                      "(up to 128 fragments; longer lists use register blocks); register_block: blocks of "
                      "block_size fragments sorted by their network in registers, written back sorted and "
                      "merged (Knowles et al. 2014)"),
          kBlockSizes.spec("block_size", 16, "sort=register_block: fragments per register block"),
          ParamSpec::boolean("backwards_allocation", true,
                             "resolve each 4x4 tile with the smallest array that holds its longest list (backwards "
                             "memory allocation, Knowles et al. 2013; 0/1-fragment tiles unsorted); false: one "
                             "full-screen resolve sized for the frame's longest list"),
          kSlotFills.spec("fill", SlotFill::automatic,
                      "how a fragment takes its slot: atomic: an atomic increment of its pixel's cursor; "
                      "framebuffer_fetch: the cursor is the pixel's R32UI colour, read and incremented in primitive "
                      "order through GL_EXT_shader_framebuffer_fetch, no atomic; auto: framebuffer_fetch where the "
                      "device has it, else atomic"),
          kScans.spec("scan", Scan::automatic,
                      "where the per-pixel counts become offsets: compute: a work-efficient prefix sum in compute "
                      "shaders; host: summed on the host from the counts read back for the pool size, then "
                      "uploaded; auto: host on a software rasterizer, compute on a GPU"),
          kKeyFormats.spec("key_format", KeyFormat::automatic,
                           "flat nodes: uint64: the fill writes the 8-byte key (view depth, triangle id) as one "
                           "64-bit integer and the network sorts it by 64-bit min/max; uint32_pair: two 32-bit "
                           "words, compared word by word; auto: uint64 where the device has "
                           "GL_ARB_gpu_shader_int64"),
          ParamSpec::boolean("flat_color_nodes", true,
                             "unlit scenes (every fragment has its triangle's flat colour): 8-byte nodes holding the "
                             "sort key alone, the exact colour fetched by triangle id in the resolve; false, or lit "
                             "scenes: 24-byte nodes with the float colour")},
      .stages = {"count", "fill", "compose"},
      .exactness = Exactness::exact,
      // Speed options only (every value is exact): the GPU-style paths against llvmpipe's.
      .quality_sweep = {{"fill", {"atomic", "framebuffer_fetch"}},
                        {"scan", {"compute", "host"}},
                        {"key_format", {"uint32_pair", "uint64"}}},
      .adaptive_switches = {
          {"backwards_allocation",
           "resolves each 4x4 tile with the smallest array that holds its longest list instead of the frame's "
           "largest array everywhere",
           {{"backwards_allocation", "true"}}, {{"backwards_allocation", "false"}}},
          {"flat_color_nodes",
           "stores 8-byte keys on unlit scenes and fetches each fragment's flat colour by triangle id instead of "
           "storing 24-byte nodes with the colour",
           {{"flat_color_nodes", "true"}}, {{"flat_color_nodes", "false"}}}},
      .extra_support_check = [](const ParamSet& params, const SceneFacts&,
                                const DeviceProfile& device) { return missing_device_feature(params, device); },
      .resolve = resolve_parameters,
      .create = make_technique<LinearizedFragmentBuffer>,
      .storage_need = [](const ParamSet&, const FrameContent& content) {
        const uint64_t fragments = std::max<uint64_t>(content.fragments, 1);
        return StorageNeed{fragments * kNodeBytes, content.pixels() * kPixelBytes + fragments * kNodeBytes};
      },
  });
}

}  // namespace oit
