#pragma once
// `oitbench check-order`: renders each technique with the triangles
// submitted in several orders (and the same order twice) and reports how far
// each image moves from the original-order image. Exact techniques must not
// move beyond their tolerance; approximate ones report how much they move.
#include <string>
#include <vector>

#include "harness/app/commands.h"

namespace oit {

// Exit code of check-order (and stress) when a check failed.
inline constexpr int kExitCheckFailed = 3;

struct CheckOrderOptions {
  std::vector<std::string> techniques{"all"};
  // "key=value" or "technique.key=value", one value each (one_value_technique_params).
  std::vector<std::string> sets;
  std::string scene = "quads";
  std::vector<std::string> scene_sets;
  std::string size = "64x64";
  int seeds = 2;  // shuffled:1..N and objects_shuffled:1..N
};

struct OrderCheck {
  std::string technique;
  std::string status;             // ok, skipped, error
  std::string message;
  double repeat_difference = 0;   // same order, second frame set
  double largest_difference = 0;  // over every other order
  std::string worst_order;
  uint64_t fragments_dropped = 0;  // by the original-order frame
  bool exact = false;             // held to its exact_tolerance on this run (held_to_reference)
  bool passed = true;             // held runs: every difference within tolerance
};

std::vector<std::string> order_variants(int seeds);
// The check's kind column: "exact" (held to its tolerance), "truncated" (an
// exact class that counted dropped fragments) or "approximate".
const char* order_check_kind(const TechniqueDescriptor& technique, const OrderCheck& check);
OrderCheck check_order(Harness& harness, const TechniqueDescriptor& technique, const RunSpec& base, int seeds);
// Exit code 3 (kExitCheckFailed) when an exact technique moved beyond its
// tolerance or a technique's check ended in an error; 0 otherwise (skipped
// techniques included).
int run_check_order(const CommonOptions& common, const CheckOrderOptions& options);

}  // namespace oit
