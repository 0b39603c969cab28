#pragma once
// Per-stage timing with two clocks:
//  - gl:   GL_TIMESTAMP query pairs, read back frames later (never stalls);
//  - wall: CPU steady clock bracketed by glFinish (the only trustworthy
//          clock on Mesa llvmpipe, whose per-pass GL timestamps are wrong).
// Techniques open a ScopedStage per stage. A stage name is any snake_case
// word the technique declares in TechniqueDescriptor::stages (the registry
// checks them); each becomes a CSV row and a plot series, and the plots take
// the stage order from the CSV (the order the stages first ran).
#include <chrono>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "harness/gl/handles.h"

namespace oit {

enum class ClockKind { gl, wall, both };
ClockKind parse_clock_kind(const std::string& text);
std::string to_string(ClockKind kind);

// Whether `name` can name a stage: snake_case ([a-z][a-z0-9_]*), the form
// the CSV, its readers and the plots rely on. "total" is the harness's own.
bool is_stage_name(std::string_view name);

// Milliseconds per recorded frame for one stage (a stage that runs several
// times in a frame, e.g. one peel per layer, is summed within the frame).
struct StageSamples {
  std::vector<double> wall_ms;
  std::vector<double> gl_ms;
};

class StageClock;

class ScopedStage {
 public:
  ScopedStage(StageClock& clock, std::string_view name);
  ~ScopedStage();
  ScopedStage(const ScopedStage&) = delete;
  ScopedStage& operator=(const ScopedStage&) = delete;

 private:
  StageClock& clock_;
  size_t slot_;
};

class StageClock {
 public:
  // `declared`: the stages the technique declares (TechniqueDescriptor::
  // stages); opening any other but the harness's "total" is an error that
  // names it. Empty: any snake_case name (tests timing their own passes).
  explicit StageClock(ClockKind kind, std::vector<std::string> declared = {});
  ClockKind kind() const { return kind_; }

  // Frames opened with record=false (warm-up) time nothing but behave alike.
  void begin_frame(bool record);
  void end_frame();
  ScopedStage stage(std::string_view name) { return ScopedStage(*this, name); }

  // Reads every outstanding query and returns samples per stage name, in
  // the order stages first appeared.
  std::vector<std::pair<std::string, StageSamples>> results();

 private:
  friend class ScopedStage;
  size_t open(std::string_view name);
  void close(size_t slot);
  void collect_ready_queries(bool wait);
  GLuint acquire_query();
  size_t stage_index(std::string_view name);

  struct Interval {
    size_t stage;
    size_t frame;
    GLuint begin_query = 0, end_query = 0;
    std::chrono::steady_clock::time_point wall_begin;
  };
  ClockKind kind_;
  std::vector<std::string> declared_;
  bool recording_ = false;
  size_t frame_ = 0;  // index of the current recorded frame
  std::vector<std::string> stage_names_;
  std::vector<StageSamples> samples_;
  std::vector<Interval> open_;     // by slot
  std::vector<Interval> pending_;  // closed, GL result not read yet
  std::vector<Query> queries_;
  std::vector<GLuint> free_queries_;
};

}  // namespace oit
