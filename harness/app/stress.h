#pragma once
// `oitbench stress`: a fixed list of numerical and robustness stress cases,
// each run on every technique in its own process (so a crash or a hang is a
// verdict, not the end of the suite), judged, printed as a table and
// written to CSV.
#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <vector>

#include "harness/app/commands.h"
#include "base/params.h"

namespace oit {

struct StressCase {
  std::string name;
  std::string scene;
  RawParams scene_params;
  int width = 16;
  int height = 16;
  RawParams technique_params;  // parameter-edge cases set one parameter
  // What the case expects: an exact technique matches the reference within
  // its tolerance (or reports counted truncation); any technique returns a
  // finite image in [0, its output_max]; where a clear error is an acceptable answer
  // (non-finite input, a size beyond a technique's limits), it says so.
  std::string expectation;
  bool error_acceptable = false;
  bool reduced = false;  // part of the reduced set that runs in CI
};

// The cases: fixed scene cases, plus min/max edges of every numeric
// parameter of `technique` (from its schema).
std::vector<StressCase> stress_cases(bool full);
std::vector<StressCase> parameter_edge_cases(const TechniqueDescriptor& technique);

enum class Verdict { pass, fail, skip };
std::string to_string(Verdict verdict);

struct StressOutcome {
  std::string technique;
  std::string case_name;
  Verdict verdict = Verdict::fail;
  std::string status;   // ok / skipped / error / crashed / timeout
  double error = -1.0;  // max abs vs the reference (vs the closed form for the reference itself)
  uint64_t dropped = 0;
  std::string note;     // why
};

struct StressOptions {
  std::vector<std::string> techniques{"all"};
  bool full = false;
  std::string case_filter;  // substring of the case name
  double timeout_s = 120.0;
  std::string csv;
};

// Channel values of a result that no correct output of `technique` holds:
// not finite, below 0 or above its declared output_max (with float margins).
size_t values_outside_output_range(const TechniqueDescriptor& technique, const std::vector<float>& rgba);

// The closed-form image of a scene that has one (quads, stress_layers:
// uniform over the image), from its raw parameters; nullopt for the others.
std::optional<glm::vec4> scene_closed_form(const std::string& scene, const RawParams& raw,
                                           const glm::vec3& background);

int run_stress(const CommonOptions& common, const StressOptions& options);
// Runs one case of one technique in a child process and judges it.
StressOutcome run_stress_case(const CommonOptions& common, const TechniqueDescriptor& technique,
                              const StressCase& stress_case, double timeout_s, std::string& device);

}  // namespace oit
