#include "harness/app/doctor.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>

#include "harness/app/check_order.h"
#include "harness/app/stress.h"
#include "harness/run/gpu_clocks.h"
#include "harness/gl/gl.h"
#include "scenes/model_files.h"

namespace oit {
namespace {

// One scene the exact techniques are held to: against its closed form when
// it has one, else against the reference rendered on this device.
struct DoctorScene {
  std::string label;  // what the tables call it
  std::string scene;
  RawParams scene_params;
  std::string submission_order = "original";
};

// What the doctor found about one technique: every check's judgement.
struct Findings {
  const TechniqueDescriptor* technique = nullptr;
  RawParams params;
  int held = 0;                 // checks it was held to, and passed
  std::vector<std::string> truncated;  // scenes where it counted dropped fragments (not held)
  std::vector<std::string> skipped;    // "what: why"
  std::string worst;                   // the worst failure, "" when none
  double worst_error = -1.0;
  bool failed = false;

  void fail(const std::string& what, double error) {
    if (!failed || error > worst_error) {
      worst = what;
      worst_error = error;
    }
    failed = true;
  }
};

// The first packaged model installed (the Stanford bunny first: one closed
// scanned surface, lit), else the torus.
DoctorScene mesh_scene() {
  for (const char* name : {"bunny", "wuson", "spider", "engine"}) {
    try {
      model_path(name);
      return {std::string("model ") + name, "model", {{"name", name}}};
    } catch (const MissingModel&) {
    }
  }
  return {"torus (no packaged model installed)", "torus", {}};
}

std::vector<DoctorScene> doctor_scenes() {
  const RawParams quads = {{"layers", "32"}};
  return {{"quads 32 layers", "quads", quads},
          {"quads 32 layers, shuffled", "quads", quads, "shuffled:1"},
          {"stress_layers coplanar", "stress_layers", {{"gap", "0"}}},
          {"spheres", "spheres", {}},
          mesh_scene()};
}

// The techniques the doctor holds to exactness, from --technique.
std::vector<const TechniqueDescriptor*> exact_techniques(const std::vector<std::string>& ids) {
  std::vector<const TechniqueDescriptor*> chosen;
  for (const auto& t : builtin_techniques().all()) {
    const bool named = std::find(ids.begin(), ids.end(), "all") != ids.end() ||
                       std::find(ids.begin(), ids.end(), t.id) != ids.end();
    if (named && t.exactness != Exactness::approximate) chosen.push_back(&t);
  }
  for (const auto& id : ids)
    if (id != "all" && builtin_techniques().get(id).exactness == Exactness::approximate)
      throw std::invalid_argument("doctor: technique '" + id +
                                  "' is approximate: the doctor checks the techniques that promise exactness");
  if (chosen.empty()) throw std::invalid_argument("doctor: no exact technique selected");
  return chosen;
}

// Each technique's parameters from --set, validated as bench validates them.
std::map<std::string, RawParams> parameters_of(const std::vector<const TechniqueDescriptor*>& techniques,
                                               const std::vector<std::string>& sets) {
  SweepOptions sweep;
  sweep.techniques.clear();
  for (const auto* t : techniques) sweep.techniques.push_back(t->id);
  sweep.technique_sets = sets;
  sweep.sizes = {"16x16"};
  std::map<std::string, RawParams> params;
  for (const RunSpec& run : expand_sweep(sweep, builtin_techniques())) {
    if (params.count(run.technique) != 0)
      throw std::invalid_argument("doctor: --set gives " + run.technique +
                                  " several values of a parameter; give one value per key");
    params[run.technique] = run.params;
  }
  return params;
}

std::string params_text(const RawParams& params) {
  std::string text;
  for (const auto& [key, value] : params) text += (text.empty() ? "" : " ") + key + "=" + value;
  return text;
}

}  // namespace

std::vector<std::string> doctor_stress_cases() {
  // Depth precision under a perspective camera, coplanar ties, transmittance
  // underflow over 256 layers, and a stack as deep as the defaults' caps.
  return {"gap_eye_1e-5_nf1e3", "coplanar", "alpha_1e-4_256_layers", "layers_64"};
}

double steady_clock_resolution_ns() {
  using Clock = std::chrono::steady_clock;
  double smallest = std::numeric_limits<double>::infinity();
  Clock::time_point previous = Clock::now();
  for (int i = 0; i < 100000; ++i) {
    const Clock::time_point now = Clock::now();
    const double step = std::chrono::duration<double, std::nano>(now - previous).count();
    if (step > 0.0) smallest = std::min(smallest, step);
    previous = now;
  }
  return std::isfinite(smallest) ? smallest : 0.0;
}

double gl_timestamp_resolution_ns() {
  double smallest = std::numeric_limits<double>::infinity();
  GLint64 previous = 0;
  glGetInteger64v(GL_TIMESTAMP, &previous);
  for (int i = 0; i < 20000; ++i) {
    GLint64 now = 0;
    glGetInteger64v(GL_TIMESTAMP, &now);
    if (now > previous) smallest = std::min(smallest, double(now - previous));
    previous = now;
  }
  return std::isfinite(smallest) ? smallest : 0.0;
}

namespace {

// The stress subset, each case of each technique in its own process. It
// runs before this process opens a GL context, so the children fork from a
// clean state (as `oitbench stress` does).
std::vector<StressOutcome> run_stress_subset(const CommonOptions& common, std::vector<Findings>& findings,
                                             double timeout_s) {
  std::vector<StressCase> cases;
  for (auto& c : stress_cases(false))
    for (const auto& name : doctor_stress_cases())
      if (c.name == name) cases.push_back(c);
  if (cases.size() != doctor_stress_cases().size())
    throw std::logic_error("doctor: a stress case of doctor_stress_cases() is not in stress_cases(false)");
  std::vector<StressOutcome> outcomes;
  size_t done = 0;
  for (Findings& f : findings) {
    for (StressCase c : cases) {
      c.technique_params = f.params;
      std::fprintf(stderr, "[stress %zu/%zu] %s / %s ... ", ++done, cases.size() * findings.size(),
                   f.technique->id.c_str(), c.name.c_str());
      std::string device;
      outcomes.push_back(run_stress_case(common, *f.technique, c, timeout_s, device));
      const StressOutcome& o = outcomes.back();
      std::fprintf(stderr, "%s\n", to_string(o.verdict).c_str());
      if (o.verdict == Verdict::fail)  // a crash or a hang has no error: it counts as the worst
        f.fail("stress " + c.name + ": [" + o.status + "] " + o.note,
               o.error >= 0.0 ? o.error : std::numeric_limits<double>::infinity());
      else if (o.verdict == Verdict::skip) f.skipped.push_back("stress " + c.name + ": " + o.note);
      else if (o.note.rfind("truncated", 0) == 0) f.truncated.push_back("stress " + c.name);
      else ++f.held;
    }
  }
  return outcomes;
}

void print_device(Harness& harness) {
  const DeviceProfile& device = harness.device();
  std::printf("Device profile:\n");
  for (const auto& line : device.describe()) std::printf("  %s\n", line.c_str());
  GLint timestamp_bits = 0;
  glGetQueryiv(GL_TIMESTAMP, GL_QUERY_COUNTER_BITS, &timestamp_bits);
  std::printf("\nClocks (the harness trusts the %s clock here):\n", device.trusted_clock.c_str());
  std::printf("  gl clock (GL_TIMESTAMP, %d bits): smallest step %.0f ns\n", int(timestamp_bits),
              gl_timestamp_resolution_ns());
  std::printf("  wall clock (std::chrono::steady_clock): smallest step %.0f ns\n", steady_clock_resolution_ns());
  const ClockKind trusted = harness.default_clock();
  std::printf("  frame-overhead floor (an empty frame, median): %.4f ms on the %s clock", harness.frame_overhead_ms(trusted),
              device.trusted_clock.c_str());
  const ClockKind other = trusted == ClockKind::gl ? ClockKind::wall : ClockKind::gl;
  std::printf(", %.4f ms on the %s clock\n", harness.frame_overhead_ms(other), other == ClockKind::gl ? "gl" : "wall");
  const GpuClocks clocks;
  const auto reading = clocks.read();
  if (reading)
    std::printf("  GPU clocks (NVML): SM %u MHz, memory %u MHz, %u C\n", reading->sm_mhz, reading->memory_mhz,
                reading->temperature_c);
  else
    std::printf("  GPU clocks: NVML not available (%s)\n", clocks.unavailable_reason().c_str());
}

// Max abs difference of every channel of `image` from a uniform colour.
double difference_from(const Image& image, const glm::vec4& expected) {
  double worst = 0.0;
  for (size_t i = 0; i < image.rgba.size(); ++i)
    worst = std::max(worst, std::abs(double(image.rgba[i]) - double(expected[int(i % 4)])));
  return worst;
}

// One technique on one scene, judged by its class; prints one table row.
void check_scene(Harness& harness, Findings& f, const DoctorScene& s, int width, int height) {
  const TechniqueDescriptor& t = *f.technique;
  const auto closed_form = scene_closed_form(s.scene, s.scene_params, glm::vec3(0.0f));
  std::printf("  %-22s %-40.40s ", t.id.c_str(), s.label.c_str());
  if (t.is_reference && !closed_form) {
    std::printf("%-12s %10s %10s  %s\n", "-", "", "", "the reference itself");
    return;
  }
  RunSpec spec = single_frame(t.id, f.params, s.scene, s.scene_params, width, height);
  spec.submission_order = s.submission_order;
  const RunResult r = harness.run(spec);
  if (r.status != RunStatus::ok) {
    std::printf("%-12s %10s %10s  %s\n", to_string(r.status).c_str(), "", "", r.message.c_str());
    if (r.status == RunStatus::skipped) f.skipped.push_back(s.label + ": " + r.message);
    else f.fail(s.label + ": " + r.message, std::numeric_limits<double>::infinity());
    return;
  }
  const double error = closed_form ? difference_from(r.image, *closed_form) : r.error ? r.error->max_abs : -1.0;
  const uint64_t dropped = r.counters.fragments_dropped;
  // An exact technique covers these scenes with its caps: it may drop nothing.
  const bool dropped_within_caps = t.exactness == Exactness::exact && dropped > 0;
  const char* verdict = "exact";
  if (error < 0.0) {
    verdict = "no reference";
    f.skipped.push_back(s.label + ": " + r.message);
  } else if (dropped_within_caps || (held_to_reference(t.exactness, dropped) && error > t.exact_tolerance)) {
    verdict = "NOT EXACT";
    f.fail(s.label + (dropped_within_caps ? " (" + std::to_string(dropped) + " fragments dropped)" : ""), error);
  } else if (!held_to_reference(t.exactness, dropped)) {
    verdict = "truncated";
    f.truncated.push_back(s.label);
  } else {
    ++f.held;
  }
  std::printf("%-12s %10.3g %10llu  %s\n", verdict, error, static_cast<unsigned long long>(dropped),
              closed_form ? "vs the closed form" : "vs the reference");
}

void check_orders(Harness& harness, Findings& f, int width, int height) {
  RunSpec base = single_frame("", f.params, "quads", {{"layers", "32"}}, width, height);
  const OrderCheck c = check_order(harness, *f.technique, base, 1);
  std::printf("  %-22s %-12s ", f.technique->id.c_str(), order_check_kind(*f.technique, c));
  if (c.status != "ok") {
    std::printf("%-9s %s\n", c.status.c_str(), c.message.c_str());
    if (c.status == "skipped") f.skipped.push_back("check-order: " + c.message);
    else f.fail("check-order: " + c.message, std::numeric_limits<double>::infinity());
    return;
  }
  std::printf("%-9s %14.3g %14.3g  %s\n", c.passed ? "pass" : "FAIL", c.repeat_difference, c.largest_difference,
              c.worst_order.empty() ? "-" : c.worst_order.c_str());
  if (!c.passed) f.fail("check-order: moved under " + c.worst_order, std::max(c.repeat_difference, c.largest_difference));
  else if (c.exact) ++f.held;
  else f.truncated.push_back("check-order");
}

void print_stress(const std::vector<StressOutcome>& outcomes) {
  std::printf("\nStress subset (oitbench stress cases %s", doctor_stress_cases().front().c_str());
  for (size_t i = 1; i < doctor_stress_cases().size(); ++i) std::printf(", %s", doctor_stress_cases()[i].c_str());
  std::printf("; each in its own process):\n");
  for (const auto& o : outcomes)
    std::printf("  %-22s %-24s %-5s %s\n", o.technique.c_str(), o.case_name.c_str(), to_string(o.verdict).c_str(),
                o.note.c_str());
}

// The verdict table; returns how many techniques are not exact here.
int print_verdicts(const std::vector<Findings>& findings) {
  std::printf("\nVerdict (technique, class, verdict on this device):\n");
  int not_exact = 0;
  for (const Findings& f : findings) {
    const std::string what = f.technique->id + (f.params.empty() ? "" : " " + params_text(f.params));
    std::printf("  %-30s %-27s ", what.c_str(), to_string(f.technique->exactness));
    if (f.failed) {
      ++not_exact;
      if (std::isfinite(f.worst_error)) std::printf("NOT exact here: worst error %.3g on %s\n", f.worst_error, f.worst.c_str());
      else std::printf("NOT exact here: failed on %s\n", f.worst.c_str());
    } else if (f.held == 0) {
      std::printf("skipped: %s\n", f.skipped.empty() ? "nothing it could be held to ran" : f.skipped.front().c_str());
    } else {
      std::printf("exact here (%d checks held", f.held);
      if (!f.truncated.empty())
        std::printf("; %zu truncated with every dropped fragment counted, not held", f.truncated.size());
      if (!f.skipped.empty()) std::printf("; %zu skipped, first: %s", f.skipped.size(), f.skipped.front().c_str());
      std::printf(")\n");
    }
  }
  return not_exact;
}

}  // namespace

int run_doctor(const CommonOptions& common, const DoctorOptions& options) {
  const auto techniques = exact_techniques(options.techniques);
  const auto params = parameters_of(techniques, options.technique_sets);
  int width = 0, height = 0;
  parse_size(options.size, width, height);  // a malformed size fails before anything runs
  std::vector<Findings> findings;
  for (const auto* t : techniques) {
    Findings f;
    f.technique = t;
    f.params = params.at(t->id);
    findings.push_back(std::move(f));
  }
  const std::vector<StressOutcome> stress = run_stress_subset(common, findings, options.stress_timeout_s);

  auto context = create_headless_context(parse_device_choice(common.device), common.debug_gl);
  Harness harness(*context, builtin_techniques());
  parse_size(size_for(options.size, harness.device()), width, height);
  print_device(harness);

  std::printf("\nExactness at %dx%d (technique, scene, verdict, max abs error, fragments dropped):\n", width, height);
  for (const DoctorScene& s : doctor_scenes())
    for (Findings& f : findings) check_scene(harness, f, s, width, height);

  std::printf("\ncheck-order on quads 32 layers (same order again, then reversed, shuffled:1, objects_shuffled:1):\n");
  std::printf("  %-22s %-12s %-9s %14s %14s  %s\n", "technique", "kind", "verdict", "same order", "other orders",
              "worst order");
  for (Findings& f : findings) check_orders(harness, f, width, height);

  print_stress(stress);
  const int not_exact = print_verdicts(findings);
  std::printf("\ndevice: %s | %s\n", harness.device().renderer.c_str(),
              not_exact ? "some exact techniques are NOT exact here: do not trust their numbers" : "every checked technique keeps its class here");
  return not_exact > 0 ? 3 : 0;
}

}  // namespace oit
