#pragma once
// What `oitbench bench` (and pareto) print: a progress line per run that
// tells the runs apart (technique and scene parameters) with the elapsed time
// and an estimate of what is left, and the summary table at the end, every
// line at most kConsoleWidth columns.
#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "harness/run/runner.h"

namespace oit {

inline constexpr size_t kConsoleWidth = 120;

// The entries of canonical parameter text ("k=16 tail=drop") whose value is
// not the schema's default, in schema order: "k=8" for kbuffer k=8 tail=drop.
std::string non_default_params(const ParamSchema& schema, const std::string& canonical);

// `text` cut to `width` columns, ending in "..." when it was longer.
std::string fit(const std::string& text, size_t width);

// `text` for a console line whose first `column` columns are written: word
// wrapped at kConsoleWidth, continuation lines indented by 4.
std::string wrap_after(size_t column, const std::string& text);

// "1:05" (minutes:seconds) or "2:01:05" from seconds.
std::string clock_text(double seconds);

// `text` word wrapped to lines of at most `width` columns (a longer word
// stays whole on its own line): each of its lines keeps its own leading
// spaces and continues on lines indented by `indent` spaces.
std::string wrap_text(const std::string& text, size_t width, size_t indent);

// The width to wrap stdout to: $COLUMNS when set, else the terminal's
// width, else (not a terminal) kConsoleWidth.
size_t terminal_width();

// Elapsed time since construction and a linear estimate of the rest.
class Progress {
 public:
  using Clock = std::function<std::chrono::steady_clock::time_point()>;
  // `clock`: the time now (tests pass their own).
  explicit Progress(size_t runs, Clock clock = std::chrono::steady_clock::now);
  // "[3/12] kbuffer k=8 on quads layers=4 256x256 camera random:4:1@2 ... ",
  // cut to leave 40 columns for the outcome.
  std::string start_text(size_t index, const RunSpec& spec) const;

  // " [elapsed 0:12, ETA 0:40]" after `done` runs of the total (no ETA
  // after the last), the ETA from the time the done runs took. The clock is
  // read when the text is made: on conversion to std::string or when
  // appended to a run's outcome, so that in `run_one(spec) +
  // progress.timing_text(i + 1)` it is read after the run, whichever
  // operand C++ evaluates first.
  class Timing {
   public:
    Timing(const Progress& progress, size_t done) : progress_(progress), done_(done) {}
    std::string text() const;
    operator std::string() const { return text(); }  // NOLINT: read on conversion, by design
    friend std::string operator+(std::string outcome, const Timing& timing) { return outcome + timing.text(); }

   private:
    const Progress& progress_;
    size_t done_;
  };
  Timing timing_text(size_t done) const { return Timing(*this, done); }

 private:
  size_t runs_;
  Clock clock_;
  std::chrono::steady_clock::time_point start_;
};

// The summary table: one block per configuration (scene, its parameters,
// camera, size, scene rectangle) in the sweep's order, its runs from the
// fastest median total to the slowest (skipped and error runs last). The
// ratio column divides by `baseline`'s median in the same block; when no
// block has an ok `baseline` run it divides by the block's fastest run, and
// the header and a note say so.
void print_summary(const std::vector<RunResult>& results, const std::string& baseline,
                   const TechniqueRegistry& registry);

}  // namespace oit
