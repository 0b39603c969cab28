#include "harness/app/bench_files.h"

#include <nlohmann/json.hpp>

#include <cstdio>

#include "harness/output/output_file.h"

namespace oit {
namespace {

// Keys in the order written (the CSV's), not sorted.
using json = nlohmann::ordered_json;

// "k=16 tail=drop" -> {"k": "16", "tail": "drop"}
json params_object(const std::string& canonical) {
  json object = json::object();
  for (const auto& [name, value] : csv_pairs(canonical)) object[name] = value;
  return object;
}

json figures_object(const std::vector<Figure>& figures) {
  json object = json::object();
  for (const Figure& figure : figures) object[figure.name] = figure.value;
  return object;
}

json stage_json(const StageResult& stage) {
  const Summary& s = stage.summary;
  return {{"stage", stage.stage}, {"clock", stage.clock}, {"median_ms", s.median}, {"min_ms", s.min},
          {"p05_ms", s.p05},      {"p95_ms", s.p95},      {"mean_ms", s.mean},     {"frames", s.count},
          {"ci_low_ms", s.interval.low}, {"ci_high_ms", s.interval.high}, {"samples_ms", stage.samples_ms}};
}

json run_json(const RunResult& r, const std::string& run_id) {
  const bool ran = r.status == RunStatus::ok;
  json run = {{"run_id", run_id}, {"technique", r.spec.technique}, {"params", params_object(r.technique_params)},
              {"scene", r.spec.scene}, {"scene_params", params_object(r.scene_params)}, {"camera", r.spec.camera},
              {"width", r.spec.width}, {"height", r.spec.height}, {"scene_rect", r.spec.scene_rect},
              {"requested_params", params_object(r.requested_params)},
              {"warmup", ran ? r.warmup_frames : r.spec.warmup}, {"status", to_string(r.status)},
              {"message", r.message}, {"noisy", r.noisy}, {"warnings", r.warnings}, {"rounds", r.rounds},
              {"frame_rounds", r.frame_rounds}};
  run["precision_reached"] = r.spec.precision > 0.0 ? json(r.precision_reached) : json(nullptr);
  run["ratio"] = r.ratio ? json{{"baseline", r.baseline}, {"ratio", r.ratio->ratio},
                                {"ci_low", r.ratio->interval.low}, {"ci_high", r.ratio->interval.high}}
                         : json(nullptr);
  run["frame_overhead_ms"] = r.frame_overhead_ms ? json(*r.frame_overhead_ms) : json(nullptr);
  auto clocks = [](const std::optional<GpuClockReading>& c) {
    return c ? json{{"sm_mhz", c->sm_mhz}, {"memory_mhz", c->memory_mhz}, {"temperature_c", c->temperature_c}}
             : json(nullptr);
  };
  run["gpu_clocks"] = {{"start", clocks(r.gpu_start)}, {"end", clocks(r.gpu_end)}};
  run["tiles"] = ran ? json(r.tiles) : json(nullptr);
  run["other_cpu_load"] = r.other_process_load >= 0.0 ? json(r.other_process_load) : json(nullptr);
  run["clock_disagreement"] = r.clock_disagreement ? json(*r.clock_disagreement) : json(nullptr);
  run["error"] = r.error ? json{{"max", r.error->max_abs}, {"rmse", r.error->rmse}, {"psnr", r.error->psnr_db},
                                {"ssim", r.error->ssim}, {"pixels_over_1_255", r.error->share_over_1_255}}
                         : json(nullptr);
  run["stages"] = json::array();
  for (const StageResult& stage : r.stages) run["stages"].push_back(stage_json(stage));
  if (!ran) return run;
  run.update({{"fragments", r.scene_fragments}, {"max_depth_complexity", r.max_depth_complexity},
              {"mean_depth_complexity", r.mean_depth_complexity}, {"psi", r.psi},
              {"bytes_allocated", r.counters.bytes_allocated}, {"fragments_stored", r.counters.fragments_stored},
              {"fragments_dropped", r.counters.fragments_dropped}, {"passes", r.counters.passes},
              {"overflow_retries", r.counters.overflow_retries}, {"work_saved", figures_object(r.counters.work_saved)},
              {"extra", figures_object(r.counters.extra)}});
  return run;
}

}  // namespace

const std::vector<std::string>& sample_columns() {
  static const std::vector<std::string> columns = {"run_id", "technique", "params", "scene",  "scene_params",
                                                   "camera", "width",     "height", "scene_rect", "clock",
                                                   "stage",  "frame",     "ms"};
  return columns;
}

SamplesCsv::SamplesCsv(const std::string& path) : csv_(path, sample_columns(), "samples CSV") {}

void SamplesCsv::append(const RunResult& r, const std::string& run_id) {
  std::vector<std::vector<std::string>> rows;
  for (const StageResult& stage : r.stages) {
    for (size_t frame = 0; frame < stage.samples_ms.size(); ++frame) {
      char ms[32];
      std::snprintf(ms, sizeof ms, "%.9g", stage.samples_ms[frame]);
      rows.push_back({run_id, r.spec.technique, r.technique_params, r.spec.scene, r.scene_params, r.spec.camera,
                      std::to_string(r.spec.width), std::to_string(r.spec.height), r.spec.scene_rect ? "on" : "off",
                      stage.clock, stage.stage, std::to_string(frame), ms});
    }
  }
  if (!rows.empty()) csv_.append(rows);
}

struct BenchJson::Document {
  json root;
};

BenchJson::BenchJson(std::string path, const RunContext& context)
    : path_(std::move(path)), document_(std::make_unique<Document>()) {
  document_->root = {{"device", context.device},   {"gl_version", context.gl_version},
                     {"platform", context.platform}, {"git_revision", context.git_revision},
                     {"timestamp", context.timestamp}, {"runs", json::array()}};
  write_file_atomically(path_, document_->root.dump(2) + "\n");  // a bad path fails before the first run
}

BenchJson::~BenchJson() = default;

void BenchJson::add(const RunResult& result, const std::string& run_id) {
  document_->root["runs"].push_back(run_json(result, run_id));
  write_file_atomically(path_, document_->root.dump(2) + "\n");
}

}  // namespace oit
