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

#include "harness/app/huge_page_malloc.h"
#include "harness/app/sweep.h"
#include "harness/app/sweep_cli.h"

namespace {

std::string benchmark_name(const oit::RunSpec& spec) {
  return oit::run_name(spec, {"/", ":", "/scene:", "/camera:", "/scene_rect:off"});
}

// One frame per benchmark iteration: a trial of N iterations is one harness
// run of N timed frames (after the run's warm-up), whose per-frame totals
// are reported as the iterations' manual times.
void run_benchmark(benchmark::State& state, oit::Harness* harness, oit::RunSpec spec) {
  spec.frames = int(state.max_iterations);
  const oit::RunResult result = harness->run(spec);
  if (result.status != oit::RunStatus::ok) {
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
  // No reference (it could not be made at this size): NaN, as its CSV columns are empty.
  state.counters["error_max"] = result.error ? result.error->max_abs : std::nan("");
  state.counters["error_rmse"] = result.error ? result.error->rmse : std::nan("");
  state.SetLabel(result.clock == oit::ClockKind::gl ? "clock=gl" : "clock=wall");
}

}  // namespace

int main(int argc, char** argv) {
  oit::relaunch_with_huge_page_malloc(argv);
  CLI::App app{"oitbench_gbench: oitbench runs as Google Benchmark benchmarks (its --benchmark_* flags apply; "
               "without --frames, --benchmark_min_time decides how many frames a run times)",
               "oitbench_gbench"};
  app.option_defaults()->always_capture_default();
  oit::SweepOptions sweep;
  std::string device = "auto";
  oit::add_sweep_cli_options(&app, sweep);
  app.add_option("--device", device, "auto, gpu, software or egl:N");
  app.get_option("--frames")
      ->description("timed frames per run, fixed (Iterations(N)); without it --benchmark_min_time decides")
      ->default_str("");
  // --help: the sweep options here, then Google Benchmark's flags, which
  // benchmark::Initialize prints before it exits.
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--help") std::printf("%s\nGoogle Benchmark's flags:\n", app.help().c_str());
  std::fflush(stdout);
  benchmark::Initialize(&argc, argv);
  CLI11_PARSE(app, argc, argv);
  const bool fixed_frames = app.count("--frames") > 0;
  try {
    // Every combination is checked before a context opens.
    const std::vector<oit::RunSpec> runs = oit::expand_sweep(sweep, oit::builtin_techniques());
    auto context = oit::create_headless_context(oit::parse_device_choice(device));
    oit::Harness harness(*context, oit::builtin_techniques());
    for (const auto& spec : runs) {
      auto* benchmark = benchmark::RegisterBenchmark(benchmark_name(spec).c_str(), run_benchmark, &harness, spec)
                            ->UseManualTime()
                            ->Unit(benchmark::kMillisecond);
      if (fixed_frames) benchmark->Iterations(sweep.frames);
    }
    benchmark::AddCustomContext("device", harness.device().renderer);
    // Debian's libbenchmark is compiled without NDEBUG, so the library warns
    // that it "was built as DEBUG": that concerns its own bookkeeping, which
    // manual time leaves out (the times are the stage clock's).
    benchmark::AddCustomContext("timing", "manual: oitbench's per-frame stage clock total");
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "oitbench_gbench: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
