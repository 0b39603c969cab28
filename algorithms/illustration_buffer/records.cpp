#include "algorithms/illustration_buffer/records.h"

#include "algorithms/illustration_buffer/bindings.h"
#include "harness/gl/check.h"

namespace oit::illustration_buffer {

uint64_t bytes_per_fragment(const Settings& s) {
  return uint64_t((s.ranged() ? 0 : kNextBytes) + kFragmentBytes + kSearchBytes + kShadeBytes +
                  (s.measure_accuracy ? kTruthBytes : 0) + (s.may_sweep() ? kDistanceBytes : 0));
}

// Per pixel: head and count; with storage=linearized the counting pass's
// R32F count, the fill's offset and its cursor, and an entry in the list of
// covered pixels (pixel_dispatch.glsl); with arrays the same but the count
// target (the offsets buffer holds the fill's counts); plus (when the diffusion
// skips converged fragments) a stamp, an entry in each of three worklists,
// an update count and a seed mark (stylize_seed_queue.comp).
uint64_t bytes_per_pixel(const Settings& s) {
  return 8 + (s.linearized() ? 16 : s.arrays() ? 12 : 0) + (s.tracks_convergence() ? 24 : 0);
}

Records::Records(const Settings& settings)
    : counters(make_buffer(kCounterBytes)),
      s_(settings),
      pool_("illustration_buffer",
            s_.linearized() ? FragmentPool::Sizing::exact
            : s_.arrays()   ? FragmentPool::Sizing::fixed  // slots per pixel (FillStage)
                            : FragmentPool::Sizing::previous_frame,
            kLargestRecordBytes, [this](uint64_t capacity) { allocate(capacity); }, kSmallestPool) {}

void Records::resize(int width, int height) {
  width_ = width;
  height_ = height;
  const GLsizeiptr bytes = GLsizeiptr(width) * height * 4;
  head = make_buffer(bytes);
  count = make_buffer(bytes);
  head_view = make_buffer_texture(head, GL_R32UI, 0, bytes);
  count_view = make_buffer_texture(count, GL_R32UI, 0, bytes);
  pool_.reset(s_.linearized() ? 1 : uint64_t(width) * uint64_t(height) * s_.initial_nodes_per_pixel);
}

void Records::allocate(uint64_t capacity) {
  if (!s_.ranged()) next_ = make_buffer(GLsizeiptr(capacity) * kNextBytes);  // sort=dynamic's lists
  data_ = make_buffer(GLsizeiptr(capacity) * kFragmentBytes);
  data2_ = make_buffer(GLsizeiptr(capacity) * kSearchBytes);
  data3_ = make_buffer(GLsizeiptr(capacity) * kShadeBytes);
  if (s_.measure_accuracy) truth_ = make_buffer(GLsizeiptr(capacity) * kTruthBytes);
  gl_check("allocating the illustration buffer's fragment pool");
  fragment_view = make_buffer_texture(data_, GL_RGBA32UI, 0, GLsizeiptr(capacity) * kFragmentBytes);
  search_view_ = make_buffer_texture(data2_, GL_RGBA32UI, 0, GLsizeiptr(capacity) * kSearchBytes);
  shade_view_ = make_buffer_texture(data3_, GL_RGBA32UI, 0, GLsizeiptr(capacity) * kShadeBytes);
  const GLsizeiptr field_bytes = kFieldBytes * GLsizeiptr(capacity);
  fields_view_[0] = make_buffer_texture(data_, GL_RGBA32F, 0, field_bytes);
  fields_view_[1] = make_buffer_texture(data_, GL_RGBA32F, second_field_range(), field_bytes);
  gl_check("creating the illustration buffer's read-only views");
}

void Records::bind_storage() const {
  bind_storage_buffers({{IB_HEAD_BINDING, &head},
                        {IB_COUNT_BINDING, &count},
                        {IB_NEXT_BINDING, &next_},
                        {IB_DATA_BINDING, &data_},
                        {IB_DATA2_BINDING, &data2_},
                        {IB_DATA3_BINDING, &data3_},
                        {IB_COUNTERS_BINDING, &counters}});
  if (truth_) bind_storage_buffers({{IB_TRUTH_BINDING, &truth_}});
}

void Records::bind_sorted_views() const {
  glBindTextureUnit(IB_SEARCH_UNIT, search_view_.id());
  glBindTextureUnit(IB_SHADE_UNIT, shade_view_.id());
  glBindTextureUnit(IB_HEAD_UNIT, head_view.id());
  glBindTextureUnit(IB_COUNT_UNIT, count_view.id());
}

void Records::bind_fields(GLintptr in, GLintptr out, uint64_t stored) const {
  const GLsizeiptr bytes = std::max<GLsizeiptr>(kFieldBytes * GLsizeiptr(stored), kFieldBytes);
  glBindBufferRange(GL_SHADER_STORAGE_BUFFER, IB_FIELDS_IN_BINDING, data_.id(), in, bytes);
  glBindBufferRange(GL_SHADER_STORAGE_BUFFER, IB_FIELDS_OUT_BINDING, data_.id(), out, bytes);
  glBindTextureUnit(IB_FIELDS_UNIT, in == 0 ? fields_view_[0].id() : fields_view_[1].id());
}

GLintptr Records::second_field_range() const {
  GLint storage = 1, texture = 1;
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &storage);
  glGetIntegerv(GL_TEXTURE_BUFFER_OFFSET_ALIGNMENT, &texture);
  const GLintptr alignment = std::max({storage, texture, 1});
  const GLintptr offset = kFieldBytes * GLintptr(pool_.capacity());
  return (offset + alignment - 1) / alignment * alignment;
}

void Records::copy_fields(GLintptr from, GLintptr to, uint64_t stored) const {
  glCopyNamedBufferSubData(data_.id(), data_.id(), from, to, kFieldBytes * GLsizeiptr(stored));
}

void Records::read_lists(uint64_t stored, std::vector<uint32_t>& first, std::vector<uint32_t>& count_out,
                         std::vector<SortedRecord>& sorted) const {
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  const size_t pixels = size_t(width_) * size_t(height_);
  first.assign(pixels, 0);
  count_out.assign(pixels, 0);
  std::vector<SortedSearchRecord> search(stored);
  std::vector<SortedShadeRecord> shade(stored);
  glGetNamedBufferSubData(head.id(), 0, GLsizeiptr(pixels * 4), first.data());
  glGetNamedBufferSubData(count.id(), 0, GLsizeiptr(pixels * 4), count_out.data());
  if (stored > 0) {
    glGetNamedBufferSubData(data2_.id(), 0, GLsizeiptr(search.size() * sizeof(SortedSearchRecord)), search.data());
    glGetNamedBufferSubData(data3_.id(), 0, GLsizeiptr(shade.size() * sizeof(SortedShadeRecord)), shade.data());
  }
  gl_check("illustration_buffer: reading back the sorted lists");
  sorted.resize(stored);
  for (size_t i = 0; i < sorted.size(); ++i) sorted[i] = join(search[i], shade[i]);
}

std::vector<uint32_t> Records::read_counts() const {
  std::vector<uint32_t> counts(size_t(width_) * size_t(height_));
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  if (!counts.empty()) glGetNamedBufferSubData(count.id(), 0, GLsizeiptr(counts.size() * 4), counts.data());
  gl_check("illustration_buffer: reading back the list lengths");
  return counts;
}

std::vector<TruthRecord> Records::read_truth(uint64_t produced) const {
  std::vector<TruthRecord> truth(s_.measure_accuracy ? produced : 0);
  if (!truth.empty())
    glGetNamedBufferSubData(truth_.id(), 0, GLsizeiptr(truth.size() * sizeof(TruthRecord)), truth.data());
  gl_check("illustration_buffer: reading back the truth records for the neighbour statistics");
  return truth;
}

}  // namespace oit::illustration_buffer
