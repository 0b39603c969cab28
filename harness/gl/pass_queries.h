#pragma once
// One GL_SAMPLES_PASSED query per pass of a multi-pass technique (the
// peeling techniques count what each pass peeled or selected), made when a
// pass first needs it and reused every frame. A result waits for its pass,
// so techniques read them in counters(), outside the timed frame, or right
// after a pass when early exit must know.
#include <cstdint>
#include <vector>

#include "harness/gl/handles.h"

namespace oit {

class PassSampleQueries {
 public:
  // The query of pass `index` (numbered as the caller likes, from 0).
  const Query& at(size_t index) {
    while (queries_.size() <= index) queries_.push_back(make_query(GL_SAMPLES_PASSED));
    return queries_[index];
  }
  // Samples counted by pass `index` (waits for it).
  uint64_t result(size_t index) const {
    GLuint samples = 0;
    glGetQueryObjectuiv(queries_.at(index).id(), GL_QUERY_RESULT, &samples);
    return samples;
  }
  // Samples counted by passes first .. end - 1 (0 when the range is empty).
  uint64_t sum(size_t first, size_t end) const {
    uint64_t total = 0;
    for (size_t index = first; index < end; ++index) total += result(index);
    return total;
  }

 private:
  std::vector<Query> queries_;
};

}  // namespace oit
