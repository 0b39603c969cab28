// `oitbench adaptive`: scene specs, and the command as users call it: the
// table and the CSV rows of a technique switch and of the harness's scene
// rectangle, each on and off, and a model that is not installed.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "harness/app/adaptive.h"
#include "harness/run/results_csv.h"
#include "tests/oitbench_process.h"

namespace oit {
namespace {

using test::Outcome;

const std::string kOut = std::string(OIT_BINARY_DIR) + "/test_output/adaptive";

Outcome run_oitbench(const std::string& environment, const std::string& arguments) {
  return test::run_oitbench(kOut, arguments, environment);
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, separator)) parts.push_back(part);
  return parts;
}

// The table line of technique/feature/scene, split on blanks.
std::vector<std::string> table_line(const std::string& output, const std::string& technique,
                                    const std::string& feature, const std::string& scene) {
  for (const auto& line : split(output, '\n')) {
    std::vector<std::string> words;
    std::stringstream in(line);
    for (std::string word; in >> word;) words.push_back(word);
    if (words.size() >= 3 && words[0] == technique && words[1] == feature && words[2] == scene) return words;
  }
  return {};
}

TEST(AdaptiveSceneSpec, IdAndParameters) {
  std::string scene;
  RawParams params;
  parse_scene_spec("quads:layers=4,alpha=0.5", scene, params);
  EXPECT_EQ(scene, "quads");
  EXPECT_EQ(params, (RawParams{{"layers", "4"}, {"alpha", "0.5"}}));
  params.clear();
  parse_scene_spec("torus", scene, params);
  EXPECT_EQ(scene, "torus");
  EXPECT_TRUE(params.empty());
  EXPECT_THROW(parse_scene_spec("quads:layers", scene, params), std::invalid_argument);
  EXPECT_THROW(parse_scene_spec(":layers=4", scene, params), std::invalid_argument);
}

TEST(AdaptiveCommand, EarlyExitAndSceneRectOnAndOffInTheTableAndTheCsv) {
  const std::string csv = kOut + "/depth_peeling.csv";
  std::filesystem::remove(csv);
  const Outcome o = run_oitbench("", "adaptive --technique depth_peeling --scene quads:layers=4 --size 32x32 "
                                     "--frames 1 --warmup 0 --repeats 2 --csv " + csv);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  // technique feature scene on_ms off_ms time on_bytes off_bytes memory max_diff [work saved]
  const auto early = table_line(o.output, "depth_peeling", "early_exit", "quads:layers=4");
  ASSERT_GE(early.size(), 10u) << o.output;
  EXPECT_EQ(early[9], "0") << "early exit changed the image:\n" << o.output;
  EXPECT_EQ(early[6], early[7]);  // the same targets either way
  EXPECT_EQ(early[8], "1.000");
  const auto rect = table_line(o.output, "depth_peeling", "scene_rect", "quads:layers=4");
  ASSERT_EQ(rect.size(), 11u) << o.output;
  EXPECT_EQ(rect[9], "0");
  EXPECT_EQ(rect[10], "pixels_outside_scene_rect=0");  // the quads cover the whole image

  const test::CsvTable table = test::read_csv_table(csv);
  ASSERT_EQ(table.header, csv_columns());
  auto column = [&](const std::string& name) { return table.column(name); };
  // Passes of every run's total row, by configuration: each side twice.
  std::map<std::string, std::vector<std::string>> passes;
  for (const auto& row : table.rows) {
    ASSERT_EQ(row.size(), table.header.size());
    EXPECT_EQ(row[column("status")], "ok") << row[column("message")];
    EXPECT_EQ(row[column("scene_params")].find("layers=4"), 0u) << row[column("scene_params")];
    if (row[column("stage")] != "total") continue;
    const std::string params = row[column("params")];
    const bool early_exit = params.find("early_exit=true") != std::string::npos;
    passes[std::string(early_exit ? "early_exit=true" : "early_exit=false") + " scene_rect=" +
           row[column("scene_rect")]]
        .push_back(row[column("passes")]);
  }
  // Early exit with the default tie_break=triangle_id: d + 2 = 6 passes for
  // 4 layers (see algorithms/depth_peeling/README.md); without it all 64.
  EXPECT_EQ(passes["early_exit=true scene_rect=on"],
            (std::vector<std::string>{"6", "6", "6", "6"}));  // 2 from early_exit on, 2 from scene_rect on
  EXPECT_EQ(passes["early_exit=false scene_rect=on"], (std::vector<std::string>{"64", "64"}));
  EXPECT_EQ(passes["early_exit=true scene_rect=off"], (std::vector<std::string>{"6", "6"}));
  EXPECT_EQ(passes.size(), 3u);
}

TEST(AdaptiveCommand, AModelThatIsNotInstalledIsASkippedRowNotACrash) {
  const Outcome o = run_oitbench("OIT_MODEL_DIR=" + kOut + "/no_models",
                                 "adaptive --technique depth_peeling --feature early_exit --scene model:name=elephant "
                                 "--scene quads:layers=2 --size 8x8 --frames 1 --warmup 0 --repeats 1");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto skipped = table_line(o.output, "depth_peeling", "early_exit", "model:name=elephant");
  ASSERT_GE(skipped.size(), 5u) << o.output;
  EXPECT_EQ(skipped[3], "skipped:");
  EXPECT_NE(o.output.find("libcgal-demo"), std::string::npos) << o.output;  // says where the model comes from
  EXPECT_GE(table_line(o.output, "depth_peeling", "early_exit", "quads:layers=2").size(), 10u) << o.output;
  EXPECT_TRUE(table_line(o.output, "depth_peeling", "scene_rect", "quads:layers=2").empty());  // --feature
}

TEST(AdaptiveCommand, UnknownFeatureNamesTheOnesOffered) {
  const Outcome o = run_oitbench("", "adaptive --technique depth_peeling --feature nope --size 8x8");
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.output.find("early_exit, scene_rect"), std::string::npos) << o.output;
}

}  // namespace
}  // namespace oit
