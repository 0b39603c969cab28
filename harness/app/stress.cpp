#include "harness/app/stress.h"

#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <optional>
#include <tuple>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "harness/run/results_csv.h"
#include "scenes/scene_library.h"
#include "scenes/stacked_quads.h"
#include "oit_revision.h"

namespace oit {
namespace {

StressCase layers_case(std::string name, RawParams params, bool reduced, std::string expectation) {
  StressCase c;
  c.name = std::move(name);
  c.scene = "stress_layers";
  c.scene_params = std::move(params);
  c.reduced = reduced;
  c.expectation = std::move(expectation);
  return c;
}

StressCase quads_case(std::string name, int layers, int size, bool reduced, RawParams extra = {}) {
  StressCase c;
  c.name = std::move(name);
  c.scene = "quads";
  c.scene_params = std::move(extra);
  c.scene_params["layers"] = std::to_string(layers);
  c.width = c.height = size;
  c.reduced = reduced;
  c.expectation = "exact, or truncation counted in fragments_dropped; never garbage, never a hang";
  return c;
}

std::string format_output_max(double output_max) {
  if (std::isinf(output_max)) return "inf";
  char text[32];
  std::snprintf(text, sizeof text, "%g", output_max);
  return text;
}

}  // namespace

std::optional<glm::vec4> scene_closed_form(const std::string& scene, const RawParams& raw,
                                           const glm::vec3& background) {
  for (const auto& d : scene_library()) {
    if (d.id != scene) continue;
    const ParamSet values(d.params, raw, "scene '" + scene + "'");
    if (scene == "stress_layers") return stress_layers_closed_form(stress_layers_params(values), background);
    if (scene == "quads") {
      StackedQuadsParams q;
      q.layers = int(values.integer("layers"));
      q.objects = int(values.integer("objects"));
      q.seed = uint32_t(values.integer("seed"));
      q.alpha = float(values.real("alpha"));
      return stacked_quads_closed_form(q, background);
    }
  }
  return std::nullopt;
}

size_t values_outside_output_range(const TechniqueDescriptor& technique, const std::vector<float>& rgba) {
  // Float margins: compositing in float overshoots the exact bounds slightly.
  const double low = -1e-4, high = technique.output_max + 1e-3;
  size_t outside = 0;
  for (float v : rgba) outside += !(std::isfinite(v) && double(v) >= low && double(v) <= high);
  return outside;
}

namespace {

// Reads a technique result in the child and judges it; runs in the child.
StressOutcome judge(const TechniqueDescriptor& technique, const StressCase& c, const RunResult& r) {
  StressOutcome o;
  o.technique = technique.id;
  o.case_name = c.name;
  o.status = to_string(r.status);
  if (r.status == RunStatus::skipped) {
    o.verdict = Verdict::skip;
    o.note = r.message;
    return o;
  }
  if (r.status == RunStatus::error) {
    o.verdict = c.error_acceptable ? Verdict::pass : Verdict::fail;
    o.note = (c.error_acceptable ? "clear error: " : "unexpected error: ") + r.message;
    return o;
  }
  o.dropped = r.counters.fragments_dropped;
  const size_t garbage = values_outside_output_range(technique, r.image.rgba);
  if (garbage > 0) {
    o.verdict = Verdict::fail;
    o.note = std::to_string(garbage) + " channel values are not finite or outside [0, " +
             format_output_max(technique.output_max) + "]";
    return o;
  }
  o.error = r.error ? r.error->max_abs : -1.0;
  if (technique.is_reference) {
    // The reference is checked against the closed form where one exists.
    const auto expected = scene_closed_form(c.scene, c.scene_params, glm::vec3(0.0f));
    if (!expected) {
      o.verdict = Verdict::pass;
      o.note = "no closed form for this scene";
      return o;
    }
    double worst = 0.0;
    for (size_t i = 0; i < r.image.rgba.size(); ++i)
      worst = std::max(worst, std::abs(double(r.image.rgba[i]) - double((*expected)[int(i % 4)])));
    o.error = worst;
  }
  char text[160];
  if (technique.exactness == Exactness::approximate) {
    o.verdict = Verdict::pass;
    std::snprintf(text, sizeof text, "approximate: error %.3g", o.error);
  } else if (!held_to_reference(technique.exactness, o.dropped)) {
    o.verdict = Verdict::pass;
    std::snprintf(text, sizeof text, "truncated, counted: %llu fragments dropped, error %.3g",
                  static_cast<unsigned long long>(o.dropped), o.error);
  } else if (o.error <= technique.exact_tolerance) {
    o.verdict = Verdict::pass;
    std::snprintf(text, sizeof text, "exact: error %.3g", o.error);
  } else {
    o.verdict = Verdict::fail;
    std::snprintf(text, sizeof text, "error %.3g above the exact tolerance %.3g with nothing reported dropped",
                  o.error, technique.exact_tolerance);
  }
  o.note = text;
  return o;
}

constexpr char kSeparator = '\x1f';

std::string serialize(const StressOutcome& o, const std::string& device) {
  std::ostringstream out;
  out << to_string(o.verdict) << kSeparator << o.status << kSeparator << o.error << kSeparator << o.dropped
      << kSeparator << device << kSeparator << o.note;
  std::string text = out.str();
  for (char& ch : text)
    if (ch == '\n') ch = ' ';
  return text + "\n";
}

void deserialize(const std::string& line, StressOutcome& o, std::string& device) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, kSeparator)) fields.push_back(field);
  if (fields.size() < 6) throw std::runtime_error("malformed stress child output");
  o.verdict = fields[0] == "pass" ? Verdict::pass : fields[0] == "skip" ? Verdict::skip : Verdict::fail;
  o.status = fields[1];
  o.error = std::stod(fields[2]);
  o.dropped = std::stoull(fields[3]);
  device = fields[4];
  o.note = fields[5];
  while (!o.note.empty() && o.note.back() == '\n') o.note.pop_back();
}

}  // namespace

std::string to_string(Verdict verdict) {
  return verdict == Verdict::pass ? "pass" : verdict == Verdict::skip ? "skip" : "FAIL";
}

std::vector<StressCase> stress_cases(bool full) {
  const std::string exact = "exact techniques match the reference (the reference: the closed form)";
  std::vector<StressCase> cases;
  for (const char* gap : {"1e-3", "1e-5", "1e-7"}) {
    const bool reduced = std::string(gap) != "1e-7";
    cases.push_back(layers_case(std::string("gap_ndc_") + gap, {{"gap", gap}}, reduced, exact));
    for (const char* ratio : {"1e1", "1e3", "1e6"}) {
      cases.push_back(layers_case(std::string("gap_eye_") + gap + "_nf" + ratio,
                                  {{"gap", gap}, {"space", "eye"}, {"near_far_ratio", ratio}},
                                  reduced && std::string(ratio) == "1e3", exact));
    }
  }
  cases.push_back(layers_case("coplanar", {{"gap", "0"}}, true,
                              exact + "; ties broken deterministically by the stable triangle id"));
  cases.push_back(layers_case("alpha_opaque", {{"alpha", "1"}}, true, "the nearest layer only, as an opaque render"));
  StressCase tiny = layers_case("alpha_1e-4_256_layers", {{"alpha", "0.0001"}, {"layers", "256"}}, true,
                                "transmittance stays near 1 without underflow; exact techniques match");
  tiny.width = tiny.height = 8;
  cases.push_back(tiny);
  cases.push_back(layers_case("alpha_mixed", {{"alpha_mode", "mixed"}, {"layers", "16"}}, true, exact));
  cases.push_back(quads_case("layers_64", 64, 16, true));
  cases.push_back(quads_case("layers_256", 256, 8, true));
  cases.push_back(quads_case("layers_1024", 1024, 8, false));
  for (auto [w, h, reduced] : {std::tuple{1, 1, true}, {1, 4097, true}, {4097, 1, false}, {333, 177, true}}) {
    StressCase c = quads_case("size_" + std::to_string(w) + "x" + std::to_string(h), 8, 1, reduced);
    c.width = w;
    c.height = h;
    c.error_acceptable = w > 4096 || h > 4096;
    if (c.error_acceptable) c.expectation += "; a clear error about a size limit is acceptable";
    cases.push_back(c);
  }
  cases.push_back(layers_case("zero_area_triangle", {{"extra", "zero_area"}}, true, exact + "; the triangle draws nothing"));
  StressCase nan = layers_case("nan_vertex", {{"extra", "nan_vertex"}}, true, "a clear error naming the vertex");
  nan.error_acceptable = true;
  cases.push_back(nan);
  StressCase inf = layers_case("inf_vertex", {{"extra", "inf_vertex"}}, false, "a clear error naming the vertex");
  inf.error_acceptable = true;
  cases.push_back(inf);
  cases.push_back(layers_case("empty_scene", {{"extra", "empty"}}, true, "the background, nothing else"));
  cases.push_back(quads_case("single_object", 16, 16, true, {{"objects", "1"}}));
  std::vector<StressCase> selected;
  for (auto& c : cases)
    if (full || c.reduced) selected.push_back(std::move(c));
  return selected;
}

std::vector<StressCase> parameter_edge_cases(const TechniqueDescriptor& technique) {
  std::vector<StressCase> cases;
  for (const ParamSpec& p : technique.params) {
    if (p.type != ParamType::integer && p.type != ParamType::real) continue;
    for (double value : {p.min, p.max}) {
      std::ostringstream text;
      text.precision(17);
      text << (p.type == ParamType::integer ? double(int64_t(value)) : value);
      StressCase c = quads_case("param_" + p.name + "=" + text.str(), 8, 8, true);
      c.technique_params = {{p.name, text.str()}};
      c.error_acceptable = false;
      cases.push_back(c);
    }
  }
  return cases;
}

StressOutcome run_stress_case(const CommonOptions& common, const TechniqueDescriptor& technique,
                              const StressCase& c, double timeout_s, std::string& device) {
  StressOutcome outcome;
  outcome.technique = technique.id;
  outcome.case_name = c.name;
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error("stress: cannot create a pipe");
  std::fflush(nullptr);
  const pid_t child = fork();
  if (child < 0) throw std::runtime_error("stress: cannot fork");
  if (child == 0) {
    close(fds[0]);
    std::string line;
    try {
      auto context = create_headless_context(parse_device_choice(common.device));
      Harness harness(*context, builtin_techniques());
      const RunSpec spec = single_frame(technique.id, c.technique_params, c.scene, c.scene_params, c.width, c.height);
      line = serialize(judge(technique, c, harness.run(spec)), context->device().renderer);
    } catch (const std::exception& e) {
      StressOutcome o;
      o.verdict = Verdict::fail;
      o.status = "error";
      o.note = std::string("harness failed: ") + e.what();
      line = serialize(o, "");
    }
    ssize_t written = write(fds[1], line.data(), line.size());
    (void)written;
    _exit(0);
  }
  close(fds[1]);
  std::string text;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  bool timed_out = false;
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    if (poll(&p, 1, int(std::min<int64_t>(left.count(), 1000))) <= 0) continue;
    char buffer[4096];
    const ssize_t n = read(fds[0], buffer, sizeof buffer);
    if (n <= 0) break;
    text.append(buffer, size_t(n));
  }
  close(fds[0]);
  if (timed_out) kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  if (timed_out) {
    outcome.status = "timeout";
    outcome.note = "no answer within " + std::to_string(int(timeout_s)) + " s (killed)";
  } else if (WIFSIGNALED(status) || text.empty()) {
    outcome.status = "crashed";
    outcome.note = WIFSIGNALED(status) ? "crashed with signal " + std::to_string(WTERMSIG(status))
                                       : "exited without an answer";
  } else {
    deserialize(text, outcome, device);
  }
  return outcome;
}

int run_stress(const CommonOptions& common, const StressOptions& options) {
  const TechniqueRegistry& registry = builtin_techniques();
  std::vector<const TechniqueDescriptor*> techniques;
  for (const auto& id : options.techniques) {
    if (id == "all")
      for (const auto& t : registry.all()) techniques.push_back(&t);
    else
      techniques.push_back(&registry.get(id));
  }
  std::vector<StressOutcome> outcomes;
  std::vector<StressCase> case_order;  // for the table
  std::map<std::string, std::map<std::string, const StressOutcome*>> table;
  const std::string timestamp = utc_timestamp();
  // bench's safeguards: its own header only, one locked and checked append per case.
  std::optional<CsvAppender> csv;
  if (!options.csv.empty())
    csv.emplace(options.csv,
                std::vector<std::string>{"timestamp", "git_revision", "device", "technique", "case", "scene",
                                         "scene_params", "width", "height", "technique_params", "expectation",
                                         "verdict", "status", "error_max", "fragments_dropped", "note"},
                "stress CSV");
  std::string device = "unknown";
  size_t failures = 0, done = 0;
  std::vector<std::pair<const TechniqueDescriptor*, StressCase>> runs;
  for (const auto* t : techniques) {
    std::vector<StressCase> cases = stress_cases(options.full);
    for (auto& edge : parameter_edge_cases(*t)) cases.push_back(edge);
    for (auto& c : cases)
      if (options.case_filter.empty() || c.name.find(options.case_filter) != std::string::npos) runs.push_back({t, c});
  }
  if (runs.empty())
    throw std::invalid_argument("stress: no case matches --case '" + options.case_filter + "' for the chosen techniques");
  outcomes.reserve(runs.size());
  for (const auto& [t, c] : runs) {
    std::fprintf(stderr, "[%zu/%zu] %s / %s ... ", ++done, runs.size(), t->id.c_str(), c.name.c_str());
    outcomes.push_back(run_stress_case(common, *t, c, options.timeout_s, device));
    const StressOutcome& o = outcomes.back();
    std::fprintf(stderr, "%s (%s)\n", to_string(o.verdict).c_str(), o.note.c_str());
    failures += o.verdict == Verdict::fail;
    if (csv) {
      std::string scene_params, params;
      for (const auto& [k, v] : c.scene_params) scene_params += (scene_params.empty() ? "" : " ") + k + "=" + v;
      for (const auto& [k, v] : c.technique_params) params += (params.empty() ? "" : " ") + k + "=" + v;
      const std::vector<std::string> row = {
          timestamp, OIT_GIT_REVISION, device, t->id, c.name, c.scene, scene_params, std::to_string(c.width),
          std::to_string(c.height), params, c.expectation, to_string(o.verdict), o.status,
          o.error >= 0 ? std::to_string(o.error) : "", std::to_string(o.dropped), o.note};
      csv->append({row});
    }
  }
  // Table: cases x techniques (shared cases only; parameter edges listed after).
  std::printf("\n%-34s", "case");
  for (const auto* t : techniques) std::printf(" %-*s", int(std::max<size_t>(6, t->id.size())), t->id.c_str());
  std::printf("\n");
  std::vector<std::string> names;
  for (const auto& o : outcomes)
    if (std::find(names.begin(), names.end(), o.case_name) == names.end()) names.push_back(o.case_name);
  for (const auto& name : names) {
    std::printf("%-34.34s", name.c_str());
    for (const auto* t : techniques) {
      const StressOutcome* found = nullptr;
      for (const auto& o : outcomes)
        if (o.case_name == name && o.technique == t->id) found = &o;
      std::printf(" %-*s", int(std::max<size_t>(6, t->id.size())), found ? to_string(found->verdict).c_str() : "-");
    }
    std::printf("\n");
  }
  if (failures > 0) {
    std::printf("\nFailures:\n");
    for (const auto& o : outcomes)
      if (o.verdict == Verdict::fail)
        std::printf("  %s / %s: [%s] %s\n", o.technique.c_str(), o.case_name.c_str(), o.status.c_str(), o.note.c_str());
  }
  std::printf("\ndevice: %s | %zu runs, %zu failed%s\n", device.c_str(), outcomes.size(), failures,
              options.csv.empty() ? "" : (" | rows appended to " + options.csv).c_str());
  return failures > 0 ? 3 : 0;
}

}  // namespace oit
