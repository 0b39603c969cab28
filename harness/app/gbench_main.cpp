// The same runs as `oitbench bench`, reachable through Google Benchmark:
// one benchmark per run, manual time = the stage clock's per-frame `total`,
// counters = fragments, bytes and error. The sweep flags are those of
// `oitbench bench` (sweep_cli.h; not its files: --csv, --json, ...).
// Google Benchmark's own flags work as usual (benchmark::Initialize takes
// them out of argv before CLI11 reads the rest): --benchmark_filter,
// --benchmark_repetitions, --benchmark_format, and --benchmark_min_time,
// which picks the number of frames unless --frames fixes it.
#include <benchmark/benchmark.h>

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "harness/app/commands.h"
#include "harness/app/huge_page_malloc.h"
#include "harness/app/sweep.h"
#include "harness/app/sweep_cli.h"

namespace {

std::string benchmark_name(const oit::RunSpec& spec) {
  return oit::run_name(spec, {"/", ":", "/scene:", "/camera:", "/scene_rect:off"});
}

// Runs that ended in an error (skipped ones, which could not happen on this
// device, are no failure, as in bench).
struct Failures {
  size_t errors = 0;
};

// One frame per benchmark iteration: a trial of N iterations is one harness
// run of N timed frames (after the run's warm-up), whose per-frame totals
// are reported as the iterations' manual times.
void run_benchmark(benchmark::State& state, oit::Harness* harness, oit::RunSpec spec, Failures* failures) {
  spec.frames = int(state.max_iterations);
  const oit::RunResult result = harness->run(spec);
  if (result.status != oit::RunStatus::ok) {
    failures->errors += result.status == oit::RunStatus::error;
    state.SkipWithError((oit::to_string(result.status) + ": " + result.message).c_str());
    for (auto _ : state) {
    }
    return;
  }
  const oit::StageResult* total = result.total();
  size_t frame = 0;
  for (auto _ : state) {
    state.SetIterationTime(total->samples_ms[frame++ % total->samples_ms.size()] * 1e-3);
  }
  state.counters["fragments"] = double(result.scene_fragments);
  state.counters["bytes"] = double(result.counters.bytes_allocated);
  // No reference (it could not be made at this size): no error counters, as its CSV columns are empty.
  if (result.error) {
    state.counters["error_max"] = result.error->max_abs;
    state.counters["error_rmse"] = result.error->rmse;
  }
  state.SetLabel(result.clock == oit::ClockKind::gl ? "clock=gl" : "clock=wall");
}

// The reporter --benchmark_format picks, less every counter that is not a
// number: with --benchmark_repetitions the library's cv (stddev / mean) of
// a counter that is 0 in every repetition (unsorted's bytes, an exact
// technique's error) is 0/0, which its JSON would print as NaN, invalid JSON.
class FiniteCountersReporter final : public benchmark::BenchmarkReporter {
 public:
  explicit FiniteCountersReporter(benchmark::BenchmarkReporter* inner) : inner_(inner) {}
  bool ReportContext(const Context& context) override { return inner_->ReportContext(context); }
  void ReportRuns(const std::vector<Run>& runs) override {
    std::vector<Run> finite = runs;
    for (Run& run : finite)
      std::erase_if(run.counters, [](const auto& counter) { return !std::isfinite(counter.second.value); });
    inner_->ReportRuns(finite);
  }
  void Finalize() override { inner_->Finalize(); }

 private:
  std::unique_ptr<benchmark::BenchmarkReporter> inner_;
};

}  // namespace

int main(int argc, char** argv) {
  oit::relaunch_with_huge_page_malloc(argv);
  CLI::App app{"oitbench_gbench: oitbench runs as Google Benchmark benchmarks (its --benchmark_* flags apply; "
               "without --frames, --benchmark_min_time decides how many frames a run times)",
               "oitbench_gbench"};
  app.option_defaults()->always_capture_default();
  oit::SweepOptions sweep;
  std::string device = "auto";
  std::string csv;
  oit::add_sweep_cli_options(&app, sweep);
  app.add_option("--device", device, "auto, gpu, software or egl:N");
  app.add_option("--csv", csv,
                 "not taken here: `oitbench bench --csv FILE` with the same options writes oitbench's CSV; "
                 "--benchmark_out=FILE --benchmark_out_format=csv writes Google Benchmark's");
  app.get_option("--frames")
      ->description("timed frames per run, fixed (Iterations(N)); without it --benchmark_min_time decides")
      ->default_str("");
  // --help: the sweep options here, then Google Benchmark's flags, which
  // benchmark::Initialize prints before it exits.
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--help") std::printf("%s\nGoogle Benchmark's flags:\n", app.help().c_str());
  std::fflush(stdout);
  // Initialize takes its flags out of argv: whether --benchmark_out writes JSON (its default) is read first.
  bool out_json = false;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag.rfind("--benchmark_out=", 0) == 0) out_json = true;
  }
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag.rfind("--benchmark_out_format=", 0) == 0) out_json = out_json && flag == "--benchmark_out_format=json";
  }
  benchmark::Initialize(&argc, argv);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return oit::report_parse_error(app, e, "oitbench_gbench", argc, argv);
  }
  const bool fixed_frames = app.count("--frames") > 0;
  try {
    if (app.count("--csv") > 0)
      throw std::invalid_argument("--csv " + csv + ": oitbench_gbench writes no CSV of its own; run `oitbench bench "
                                  "--csv " + csv + "` with the same options, or give --benchmark_out=" + csv +
                                  " --benchmark_out_format=csv for Google Benchmark's");
    oit::refuse_empty_value(&app, "--memory-budget", "512M");
    // Every combination is checked before a context opens.
    const std::vector<oit::RunSpec> runs = oit::expand_sweep(sweep, oit::builtin_techniques());
    auto context = oit::create_headless_context(oit::parse_device_choice(device));
    oit::Harness harness(*context, oit::builtin_techniques());
    if (const std::string warning = oit::clock_warning(sweep.clock, harness.device()); !warning.empty())
      std::fprintf(stderr, "oitbench_gbench: %s\n", warning.c_str());
    Failures failures;
    for (const auto& spec : runs) {
      auto* benchmark =
          benchmark::RegisterBenchmark(benchmark_name(spec).c_str(), run_benchmark, &harness, spec, &failures)
              ->UseManualTime()
              ->Unit(benchmark::kMillisecond);
      if (fixed_frames) benchmark->Iterations(sweep.exact_frames);
    }
    benchmark::AddCustomContext("device", harness.device().renderer);
    // Debian's libbenchmark is compiled without NDEBUG, so the library warns
    // that it "was built as DEBUG": that concerns its own bookkeeping, which
    // manual time leaves out (the times are the stage clock's).
    benchmark::AddCustomContext("timing", "manual: oitbench's per-frame stage clock total");
    FiniteCountersReporter display(benchmark::CreateDefaultDisplayReporter());
    // --benchmark_out's JSON the same way; its other formats stay the library's.
    std::unique_ptr<FiniteCountersReporter> file;
    if (out_json) file = std::make_unique<FiniteCountersReporter>(new benchmark::JSONReporter);
    const size_t matched = benchmark::RunSpecifiedBenchmarks(&display, file.get());
    benchmark::Shutdown();
    if (matched == 0)
      throw std::invalid_argument("--benchmark_filter=" + benchmark::GetBenchmarkFilter() + " matches none of the " +
                                  std::to_string(runs.size()) + " runs (`--benchmark_list_tests` lists them)");
    if (failures.errors > 0) {
      std::fprintf(stderr, "oitbench_gbench: %zu run%s ended in an error (error_occurred in the report)\n",
                   failures.errors, failures.errors == 1 ? "" : "s");
      return oit::kExitRunsFailed;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "oitbench_gbench: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
