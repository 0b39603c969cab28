// Each technique's README (algorithms/<id>/README.md) holds its parameter
// table as `oitbench list --markdown --params <id>` prints it from the
// registry, between fixed markers, so that every parameter is described once
// (in its ParamSpec) and a README cannot drift from the schema. The
// techniques checked are the registry's, and every folder under algorithms/
// is one of them. No GL.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

#include "harness/app/commands.h"
#include "harness/toolkit/technique.h"
#include "tests/oitbench_process.h"

namespace oit {
namespace {

const std::string kOut = std::string(OIT_BINARY_DIR) + "/test_output/technique_readme";

std::string begin_marker(const std::string& id) {
  return "<!-- parameter table: oitbench list --markdown --params " + id + " -->\n";
}
const std::string kEndMarker = "<!-- end of parameter table -->";

class TechniqueReadme : public testing::TestWithParam<std::string> {};

TEST_P(TechniqueReadme, HoldsTheGeneratedParameterTable) {
  const std::string id = GetParam();
  const std::string path = std::string(OIT_SOURCE_DIR) + "/algorithms/" + id + "/README.md";
  std::ifstream readme(path);
  ASSERT_TRUE(readme) << path << " is missing: every technique folder has a README";
  const std::string text((std::istreambuf_iterator<char>(readme)), std::istreambuf_iterator<char>());
  const std::string begin = begin_marker(id);
  const size_t from = text.find(begin);
  const size_t to = text.find(kEndMarker, from == std::string::npos ? 0 : from);
  const std::string how = "add a `## Parameters` section holding the lines\n" + begin + "(the output of " +
                          "`build/harness/oitbench list --markdown --params " + id + "`)\n" + kEndMarker;
  ASSERT_NE(from, std::string::npos) << path << " lacks its parameter table's first marker: " << how;
  ASSERT_NE(to, std::string::npos) << path << " lacks its parameter table's end marker after the first: " << how;
  const std::string generated = technique_params_markdown(builtin_techniques().get(id));
  EXPECT_EQ(text.substr(from + begin.size(), to - from - begin.size()), generated)
      << path << "'s parameter table is stale: replace it with the output of "
      << "`build/harness/oitbench list --markdown --params " << id << "`";
}

INSTANTIATE_TEST_SUITE_P(EveryTechnique, TechniqueReadme, testing::ValuesIn(builtin_techniques().ids()),
                         [](const testing::TestParamInfo<std::string>& info) { return info.param; });

// A folder under algorithms/ that the registry lacks would escape the check above.
TEST(TechniqueReadmes, EveryAlgorithmFolderIsARegisteredTechnique) {
  const std::vector<std::string> ids = builtin_techniques().ids();
  const std::set<std::string> registered(ids.begin(), ids.end());
  size_t folders = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::string(OIT_SOURCE_DIR) + "/algorithms")) {
    if (!entry.is_directory()) continue;
    ++folders;
    EXPECT_TRUE(registered.count(entry.path().filename().string()))
        << entry.path() << " is a folder of algorithms/ but no registered technique";
  }
  EXPECT_EQ(folders, registered.size());
}

TEST(TechniqueReadmes, ParameterTableHasARowPerParameterAndEscapesCells) {
  TechniqueDescriptor technique;
  technique.id = "example";
  EXPECT_EQ(technique_params_markdown(technique), "`example` has no parameters.\n");
  technique.params = {ParamSpec::integer("k", 16, 1, 64, "slots per pixel | kept\nnearest first"),
                      ParamSpec::boolean("tail", false, "blend the rest")};
  EXPECT_EQ(technique_params_markdown(technique),
            "| parameter | default | range | description |\n|---|---|---|---|\n"
            "| `k` | `16` | integer in [1, 64] | slots per pixel \\| kept nearest first |\n"
            "| `tail` | `false` | true or false | blend the rest |\n");
}

TEST(TechniqueReadmes, CommandPrintsTheTableAndRefusesAnUnknownTechnique) {
  const test::Outcome table = test::run_oitbench(kOut, "list --markdown --params kbuffer");
  EXPECT_EQ(table.exit_code, 0) << table.output;
  EXPECT_EQ(table.output, technique_params_markdown(builtin_techniques().get("kbuffer")));
  const test::Outcome unknown = test::run_oitbench(kOut, "list --markdown --params kbufer");
  EXPECT_EQ(unknown.exit_code, 1) << unknown.output;
  EXPECT_NE(unknown.output.find("unknown technique 'kbufer'"), std::string::npos) << unknown.output;
  EXPECT_NE(unknown.output.find("kbuffer"), std::string::npos) << unknown.output;  // the registered ids
  const test::Outcome without_markdown = test::run_oitbench(kOut, "list --params kbuffer");
  EXPECT_NE(without_markdown.exit_code, 0) << without_markdown.output;
  EXPECT_NE(without_markdown.output.find("--markdown"), std::string::npos) << without_markdown.output;
}

}  // namespace
}  // namespace oit
