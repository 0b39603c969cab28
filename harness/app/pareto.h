#pragma once
// `oitbench pareto`: a bench whose sweep is every technique's declared
// quality knobs (TechniqueDescriptor::quality_sweep), so that run time can be
// plotted against error (analysis/pareto.py).
#include "harness/app/commands.h"

namespace oit {

// Adds "technique.knob=v1,v2,..." sets for every selected technique that
// declares quality knobs; a knob the user's --set already names (k=4 or
// kbuffer.k=4) keeps the user's values.
SweepOptions pareto_sweep(SweepOptions sweep, const TechniqueRegistry& registry);
int run_pareto(const CommonOptions& common, BenchOptions options);

}  // namespace oit
