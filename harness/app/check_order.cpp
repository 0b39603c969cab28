#include "harness/app/check_order.h"

#include <cstdio>

#include "scenes/scene_library.h"

namespace oit {

std::vector<std::string> order_variants(int seeds) {
  std::vector<std::string> orders = {"reversed"};
  for (int s = 1; s <= seeds; ++s) {
    orders.push_back("shuffled:" + std::to_string(s));
    orders.push_back("objects_shuffled:" + std::to_string(s));
  }
  return orders;
}

const char* order_check_kind(const TechniqueDescriptor& technique, const OrderCheck& check) {
  if (check.exact) return "exact";
  return technique.exactness == Exactness::approximate ? "approximate" : "truncated";
}

OrderCheck check_order(Harness& harness, const TechniqueDescriptor& technique, const RunSpec& base, int seeds) {
  OrderCheck check;
  check.technique = technique.id;
  RunSpec spec = base;
  spec.technique = technique.id;
  spec.submission_order = "original";
  const RunResult original = harness.run(spec);
  check.status = to_string(original.status);
  check.message = original.message;
  check.fragments_dropped = original.counters.fragments_dropped;
  check.exact = held_to_reference(technique.exactness, check.fragments_dropped);
  if (original.status != RunStatus::ok) return check;
  auto moved = [&](const std::string& order) {
    spec.submission_order = order;
    const RunResult other = harness.run(spec);
    if (other.status != RunStatus::ok) throw std::runtime_error(order + ": " + other.message);
    return compare_images(other.image, original.image).max_abs;
  };
  try {
    // The same order again: a deterministic technique does not flicker.
    check.repeat_difference = moved("original");
    for (const auto& order : order_variants(seeds)) {
      const double difference = moved(order);
      if (difference > check.largest_difference) {
        check.largest_difference = difference;
        check.worst_order = order;
      }
    }
  } catch (const std::exception& e) {
    check.status = "error";
    check.message = e.what();
    check.passed = false;
    return check;
  }
  const double tolerance = technique.exact_tolerance;
  check.passed = !check.exact || (check.repeat_difference <= tolerance && check.largest_difference <= tolerance);
  return check;
}

int run_check_order(const CommonOptions& common, const CheckOrderOptions& options) {
  // Every option is checked before a context opens.
  const std::vector<const TechniqueDescriptor*> techniques = selected_techniques(options.techniques, builtin_techniques());
  const std::vector<RawParams> params = one_value_technique_params(options.sets, techniques, builtin_techniques());
  RunSpec base;
  base.scene = options.scene;
  base.scene_params = one_value_scene_params(options.scene_sets, options.scene);
  canonical_scene_params(base.scene, base.scene_params);
  for (size_t i = 0; i < techniques.size(); ++i)
    ParamSet(techniques[i]->params, params[i], "technique '" + techniques[i]->id + "'");
  parse_size(options.size, base.width, base.height);
  base.warmup = 0;
  base.frames = 1;
  auto context = create_headless_context(parse_device_choice(common.device), common.debug_gl);
  Harness harness(*context, builtin_techniques());
  parse_size(size_for(options.size, harness.device()), base.width, base.height);
  int failures = 0;
  std::printf("%-22s %-12s %-9s %14s %14s  %s\n", "technique", "kind", "verdict", "same order", "other orders",
              "worst order / message");
  for (size_t i = 0; i < techniques.size(); ++i) {
    const TechniqueDescriptor* t = techniques[i];
    RunSpec spec = base;
    spec.params = params[i];
    const OrderCheck c = check_order(harness, *t, spec, options.seeds);
    const char* verdict = c.status != "ok" ? c.status.c_str() : c.passed ? "pass" : "FAIL";
    // A technique that could not be checked is no pass: an error counts as a failure.
    failures += (c.status == "ok" && !c.passed) || c.status == "error";
    if (c.status == "ok") {
      std::printf("%-22s %-12s %-9s %14.3g %14.3g  %s\n", t->id.c_str(), order_check_kind(*t, c), verdict,
                  c.repeat_difference, c.largest_difference, c.worst_order.empty() ? "-" : c.worst_order.c_str());
    } else {
      std::printf("%-22s %-12s %-9s %14s %14s  %s\n", t->id.c_str(), order_check_kind(*t, c), verdict, "",
                  "", c.message.c_str());
    }
  }
  std::printf("\nlargest max-abs difference from the original-order image over: the same order again, reversed, "
              "shuffled:1..%d, objects_shuffled:1..%d | %s %s %s | device: %s\n",
              options.seeds, options.seeds, options.scene.c_str(), options.size.c_str(),
              failures ? "| FAIL: an exact technique moved or a check ended in an error" : "",
              harness.device().renderer.c_str());
  return failures > 0 ? kExitCheckFailed : 0;
}

}  // namespace oit
