#include "harness/toolkit/stage_clock.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "base/params.h"

namespace oit {

namespace {
const Choices<ClockKind>& clock_kinds() {
  static const Choices<ClockKind> kinds = {{ClockKind::gl, "gl"}, {ClockKind::wall, "wall"}, {ClockKind::both, "both"}};
  return kinds;
}
}  // namespace

ClockKind parse_clock_kind(const std::string& text) {
  if (const ClockKind* kind = clock_kinds().find(text)) return *kind;
  std::string names;
  for (const std::string& name : clock_kinds().names()) names += (names.empty() ? "" : ", ") + name;
  throw std::invalid_argument("clock '" + text + "' is not one of " + names);
}

std::string to_string(ClockKind kind) { return clock_kinds().name(kind); }

bool is_stage_name(std::string_view name) {
  if (name.empty() || name.front() < 'a' || name.front() > 'z') return false;
  return std::all_of(name.begin(), name.end(),
                     [](char c) { return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_'; });
}

ScopedStage::ScopedStage(StageClock& clock, std::string_view name) : clock_(clock), slot_(clock.open(name)) {}
ScopedStage::~ScopedStage() { clock_.close(slot_); }

StageClock::StageClock(ClockKind kind, std::vector<std::string> declared)
    : kind_(kind), declared_(std::move(declared)) {}

void StageClock::begin_frame(bool record) {
  recording_ = record;
  if (record) {
    for (auto& s : samples_) {
      s.wall_ms.push_back(0.0);
      s.gl_ms.push_back(0.0);
    }
  }
  // Results of earlier frames are usually ready now: read them without waiting.
  collect_ready_queries(false);
}

void StageClock::end_frame() {
  if (!open_.empty()) throw std::logic_error("a stage is still open at the end of a frame");
  if (recording_) ++frame_;
}

size_t StageClock::stage_index(std::string_view name) {
  if (!is_stage_name(name)) {
    throw std::logic_error("stage name '" + std::string(name) + "' is not snake_case ([a-z][a-z0-9_]*)");
  }
  if (!declared_.empty() && name != "total" &&
      std::find(declared_.begin(), declared_.end(), name) == declared_.end()) {
    std::string list;
    for (const auto& stage : declared_) list += (list.empty() ? "" : ", ") + stage;
    throw std::logic_error("stage '" + std::string(name) + "' is not among the stages the technique declares (" +
                           list + ")");
  }
  for (size_t i = 0; i < stage_names_.size(); ++i)
    if (stage_names_[i] == name) return i;
  stage_names_.emplace_back(name);
  // A stage first seen mid-run gets zeros for the frames it did not run in.
  samples_.push_back({std::vector<double>(frame_ + (recording_ ? 1 : 0), 0.0),
                      std::vector<double>(frame_ + (recording_ ? 1 : 0), 0.0)});
  return stage_names_.size() - 1;
}

GLuint StageClock::acquire_query() {
  if (free_queries_.empty()) {
    queries_.push_back(make_query(GL_TIMESTAMP));
    return queries_.back().id();
  }
  GLuint id = free_queries_.back();
  free_queries_.pop_back();
  return id;
}

size_t StageClock::open(std::string_view name) {
  Interval interval{stage_index(name), frame_, 0, 0, {}};
  if (recording_ && kind_ != ClockKind::wall) {
    interval.begin_query = acquire_query();
    glQueryCounter(interval.begin_query, GL_TIMESTAMP);
  }
  if (kind_ != ClockKind::gl) {
    glFinish();  // the stage starts with an idle GPU
    interval.wall_begin = std::chrono::steady_clock::now();
  }
  open_.push_back(interval);
  return open_.size() - 1;
}

void StageClock::close(size_t slot) {
  if (slot + 1 != open_.size()) throw std::logic_error("stages must close in reverse order of opening");
  Interval interval = open_.back();
  open_.pop_back();
  if (kind_ != ClockKind::gl) {
    glFinish();
    const auto now = std::chrono::steady_clock::now();
    if (recording_) {
      samples_[interval.stage].wall_ms[interval.frame] +=
          std::chrono::duration<double, std::milli>(now - interval.wall_begin).count();
    }
  }
  if (recording_ && kind_ != ClockKind::wall) {
    interval.end_query = acquire_query();
    glQueryCounter(interval.end_query, GL_TIMESTAMP);
    pending_.push_back(interval);
  }
}

void StageClock::collect_ready_queries(bool wait) {
  auto ready = [&](const Interval& interval) {
    if (!wait) {
      GLint available = 0;
      glGetQueryObjectiv(interval.end_query, GL_QUERY_RESULT_AVAILABLE, &available);
      if (!available) return false;
    }
    GLuint64 begin = 0, end = 0;
    glGetQueryObjectui64v(interval.begin_query, GL_QUERY_RESULT, &begin);
    glGetQueryObjectui64v(interval.end_query, GL_QUERY_RESULT, &end);
    samples_[interval.stage].gl_ms[interval.frame] += double(end - begin) * 1e-6;
    free_queries_.push_back(interval.begin_query);
    free_queries_.push_back(interval.end_query);
    return true;
  };
  pending_.erase(std::remove_if(pending_.begin(), pending_.end(), ready), pending_.end());
}

std::vector<std::pair<std::string, StageSamples>> StageClock::results() {
  collect_ready_queries(true);
  std::vector<std::pair<std::string, StageSamples>> out;
  for (size_t i = 0; i < stage_names_.size(); ++i) {
    StageSamples s = samples_[i];
    s.wall_ms.resize(frame_);
    s.gl_ms.resize(frame_);
    out.emplace_back(stage_names_[i], std::move(s));
  }
  return out;
}

}  // namespace oit
