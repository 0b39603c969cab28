#pragma once
// `oitbench doctor`: checks this device before anyone trusts its numbers.
// It prints the device profile, the clock the harness trusts here and the
// resolution of both clocks, the frame-overhead floor and the GPU clocks;
// then holds every technique that promises exactness (Exactness::exact and
// exact_while_storage_covers) to its class on this device: against the
// closed form (stacked quads in their order and shuffled, coplanar layers)
// and against the reference (spheres, a mesh), in other submission orders
// (check-order) and on a few stress cases; and ends with a verdict per
// technique. Exit 3 when a technique is not exact here.
#include <string>
#include <vector>

#include "harness/app/commands.h"

namespace oit {

struct DoctorOptions {
  std::vector<std::string> techniques{"all"};  // the exact classes among them are checked
  // "key=value" or "technique.key=value": the parameters the checks run
  // with (one value each), e.g. to check a k or a cap on this device.
  std::vector<std::string> technique_sets;
  std::string size = "64x64";
  double stress_timeout_s = 120.0;
};

// The stress cases the doctor runs (by name, from stress_cases(false)).
std::vector<std::string> doctor_stress_cases();

// The smallest positive step of the steady clock, and of GL_TIMESTAMP on
// the current context (0 when it never advanced in the reads), in ns.
double steady_clock_resolution_ns();
double gl_timestamp_resolution_ns();

int run_doctor(const CommonOptions& common, const DoctorOptions& options);

}  // namespace oit
