#include "harness/app/pareto.h"

#include <algorithm>

namespace oit {

SweepOptions pareto_sweep(SweepOptions sweep, const TechniqueRegistry& registry) {
  const bool all = std::find(sweep.techniques.begin(), sweep.techniques.end(), "all") != sweep.techniques.end();
  for (const auto& t : registry.all()) {
    if (!all && std::find(sweep.techniques.begin(), sweep.techniques.end(), t.id) == sweep.techniques.end()) continue;
    for (const auto& [knob, values] : t.quality_sweep) {
      // A knob the user's --set gives stays at the user's values.
      const bool given = std::any_of(sweep.technique_sets.begin(), sweep.technique_sets.end(), [&](const auto& text) {
        return text.rfind(knob + "=", 0) == 0 || text.rfind(t.id + "." + knob + "=", 0) == 0;
      });
      if (given) continue;
      std::string set = t.id + "." + knob + "=";
      for (size_t i = 0; i < values.size(); ++i) set += (i ? "," : "") + values[i];
      sweep.technique_sets.push_back(set);
    }
  }
  return sweep;
}

int run_pareto(const CommonOptions& common, BenchOptions options) {
  options.sweep = pareto_sweep(options.sweep, builtin_techniques());
  return run_bench(common, options);
}

}  // namespace oit
