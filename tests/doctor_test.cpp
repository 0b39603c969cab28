// `oitbench doctor` through the command line, as on a new device: it prints
// the device profile, the clocks and the frame-overhead floor, holds every
// technique that promises exactness to its class here, and exits 3 when one
// is not exact, as a technique run with a cap below the scene's depth is.
#include <gtest/gtest.h>

#include <regex>

#include "harness/app/doctor.h"
#include "harness/app/stress.h"
#include "harness/toolkit/technique.h"
#include "tests/oitbench_process.h"

namespace oit {
namespace {

const std::string kOut = std::string(OIT_BINARY_DIR) + "/test_output/doctor";

// The verdict line of `id` (with its parameters, if any), "" when none.
std::string verdict_line(const std::string& output, const std::string& id) {
  std::smatch match;
  const std::regex line("\\n  (" + id + "(?: [^ ]+)*) +(exact|exact while storage covers) +([^\\n]*)");
  const size_t verdicts = output.find("\nVerdict");
  if (verdicts == std::string::npos) return "";
  const std::string tail = output.substr(verdicts);
  return std::regex_search(tail, match, line) ? match.str(0) : "";
}

TEST(Doctor, PassesHereWithTheProfileTheFloorAndAVerdictPerExactTechnique) {
  const test::Outcome o = test::run_oitbench(kOut, "doctor");
  EXPECT_EQ(o.exit_code, 0) << o.output;
  for (const char* printed : {"Device profile:\n  renderer: ", "trusted clock: ", "Clocks (the harness trusts the ",
                              "gl clock (GL_TIMESTAMP, ", "wall clock (std::chrono::steady_clock): smallest step ",
                              "frame-overhead floor (an empty frame, median): ", "GPU clocks", "\ncheck-order on quads",
                              "\nStress subset", "vs the closed form", "vs the reference"})
    EXPECT_NE(o.output.find(printed), std::string::npos) << printed << "\n" << o.output;
  size_t exact = 0;
  for (const auto& t : builtin_techniques().all()) {
    if (t.exactness == Exactness::approximate) continue;
    ++exact;
    const std::string line = verdict_line(o.output, t.id);
    EXPECT_NE(line.find(std::string(to_string(t.exactness)) + " "), std::string::npos) << t.id << ": " << line;
    EXPECT_NE(line.find(" exact here ("), std::string::npos) << t.id << ": " << line << "\n" << o.output;
  }
  EXPECT_GE(exact, 5u);
  // Each stress case of the subset ran for each of them.
  for (const auto& name : doctor_stress_cases())
    EXPECT_NE(o.output.find(" " + name + " "), std::string::npos) << name;
}

// linked_list is exact: with room for 4 of 32 layers it drops fragments
// on scenes its defaults cover, so it is not exact here, and the doctor says
// so and fails.
TEST(Doctor, ExitsThreeWhenAnExactTechniqueIsNotExactHere) {
  const test::Outcome o = test::run_oitbench(kOut, "doctor --technique linked_list --set linked_list.max_per_pixel=4");
  EXPECT_EQ(o.exit_code, 3) << o.output;
  const std::string line = verdict_line(o.output, "linked_list");
  EXPECT_NE(line.find("linked_list max_per_pixel=4 "), std::string::npos) << o.output;
  EXPECT_NE(line.find("NOT exact here: worst error "), std::string::npos) << line;
  EXPECT_NE(line.find(" fragments dropped)"), std::string::npos) << line;
  EXPECT_NE(o.output.find("some exact techniques are NOT exact here"), std::string::npos) << o.output;
}

TEST(Doctor, RefusesAnApproximateTechniqueAndASweptValue) {
  const test::Outcome approximate = test::run_oitbench(kOut, "doctor --technique unsorted");
  EXPECT_EQ(approximate.exit_code, 1) << approximate.output;
  EXPECT_NE(approximate.output.find("technique 'unsorted' is approximate"), std::string::npos) << approximate.output;
  const test::Outcome swept = test::run_oitbench(kOut, "doctor --technique kbuffer --set kbuffer.k=4,8");
  EXPECT_EQ(swept.exit_code, 1) << swept.output;
  EXPECT_NE(swept.output.find("give one value per key"), std::string::npos) << swept.output;
}

// The one rule every judge shares: exact classes are held to the reference
// on a run that counted no dropped fragment, approximate ones never.
TEST(ExactnessClasses, HeldToTheReferenceOnlyWithoutCountedDrops) {
  EXPECT_TRUE(held_to_reference(Exactness::exact, 0));
  EXPECT_FALSE(held_to_reference(Exactness::exact, 1));
  EXPECT_TRUE(held_to_reference(Exactness::exact_while_storage_covers, 0));
  EXPECT_FALSE(held_to_reference(Exactness::exact_while_storage_covers, 65536));
  EXPECT_FALSE(held_to_reference(Exactness::approximate, 0));
  EXPECT_STREQ(to_string(Exactness::exact_while_storage_covers), "exact while storage covers");
}

// The stress subset names cases that exist (a renamed case would make the
// doctor run nothing).
TEST(Doctor, StressSubsetNamesReducedCases) {
  const auto cases = stress_cases(false);
  for (const auto& name : doctor_stress_cases()) {
    bool found = false;
    for (const auto& c : cases) found = found || c.name == name;
    EXPECT_TRUE(found) << name;
  }
}

}  // namespace
}  // namespace oit
