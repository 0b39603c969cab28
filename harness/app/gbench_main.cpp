// The same runs as `oitbench bench`, reachable through Google Benchmark:
// one benchmark per run, manual time = the stage clock's median-free per-frame
// `total`, counters = fragments, bytes and error. Google Benchmark's own flags
// (--benchmark_filter, --benchmark_repetitions, --benchmark_format, ...) work
// as usual; benchmark::Initialize takes those out of argv and the sweep
// flags (those of `oitbench bench`, without --csv) stay for CLI11.
#include <benchmark/benchmark.h>

#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>

#include "harness/app/huge_page_malloc.h"
#include "harness/app/sweep.h"

namespace {

std::string benchmark_name(const oit::RunSpec& spec) {
  std::string name = spec.technique;
  for (const auto& [key, value] : spec.params) name += "/" + key + ":" + value;
  name += "/scene:" + spec.scene;
  for (const auto& [key, value] : spec.scene_params) name += "/" + key + ":" + value;
  name += "/" + std::to_string(spec.width) + "x" + std::to_string(spec.height);
  if (!spec.scene_rect) name += "/scene_rect:off";
  return name;
}

// One frame per benchmark iteration; the harness does the warm-up itself.
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
  benchmark::Initialize(&argc, argv);
  CLI::App app{"oitbench_gbench: oitbench runs as Google Benchmark benchmarks"};
  oit::SweepOptions sweep;
  std::string device = "auto";
  sweep.sizes = {"128x128"};
  app.add_option("--technique,-t", sweep.techniques, "technique ids or 'all'");
  app.add_option("--scene,-s", sweep.scenes, "scene ids or files");
  app.add_option("--set", sweep.technique_sets, "key=v1,v2");
  app.add_option("--scene-set", sweep.scene_sets, "scene key=v1,v2");
  app.add_option("--size", sweep.sizes, "WIDTHxHEIGHT");
  app.add_option("--warmup", sweep.warmup, "untimed frames");
  app.add_option("--scene-rect", sweep.scene_rects, "on, off or on,off (the harness's scene rectangle)")
      ->delimiter(',')
      ->check(CLI::IsMember({"on", "off"}));
  app.add_option("--clock", sweep.clock, "auto, gl or wall")->check(CLI::IsMember({"auto", "gl", "wall"}));
  app.add_option("--device", device, "auto, gpu, software or egl:N");
  CLI11_PARSE(app, argc, argv);
  try {
    auto context = oit::create_headless_context(oit::parse_device_choice(device));
    oit::Harness harness(*context, oit::builtin_techniques());
    for (const auto& spec : oit::expand_sweep(sweep, oit::builtin_techniques())) {
      benchmark::RegisterBenchmark(benchmark_name(spec).c_str(), run_benchmark, &harness, spec)
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond)
          ->Iterations(10);
    }
    benchmark::AddCustomContext("device", harness.device().renderer);
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "oitbench_gbench: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
