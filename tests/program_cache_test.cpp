// The process-wide program cache (harness/gl/program_cache.h): a program is
// compiled once per (sources, defines) and later builds come from its binary,
// render the same, fall back to compiling when the driver refuses the
// binary, and OIT_PROGRAM_CACHE=off compiles every time.
#include <gtest/gtest.h>

#include <bit>
#include <cstdlib>

#include "harness/gl/program_cache.h"
#include "harness/gl/shader_program.h"
#include "tests/gl_fixture.h"

namespace oit {
namespace {

// The red channel a full-screen draw of `program` writes.
float drawn_value(const Program& program) { return test::drawn_texel(program).r; }

Program value_program(const std::string& value) {
  return build_fullscreen_program("tests/shaders/defined_value.frag", {{"VALUE", value}});
}

class ProgramCacheTest : public ::testing::Test {
 protected:
  void SetUp() override {
    test::gl_context();
    GLint formats = 0;
    glGetIntegerv(GL_NUM_PROGRAM_BINARY_FORMATS, &formats);
    // Mesa offers its binary format when its shader cache is on (the tests set MESA_SHADER_CACHE_DIR).
    ASSERT_GT(formats, 0) << "this driver offers no program binary format: the cache cannot reuse anything";
    before_ = ProgramCache::instance().stats();
  }
  uint64_t compiled() const { return ProgramCache::instance().stats().compiled - before_.compiled; }
  uint64_t reused() const { return ProgramCache::instance().stats().reused - before_.reused; }

  ProgramCacheStats before_;
};

TEST_F(ProgramCacheTest, SameSourcesAndDefinesCompileOnceThenComeFromTheBinary) {
  const Program first = value_program("0.375");
  EXPECT_EQ(compiled(), 1u);
  EXPECT_EQ(reused(), 0u);
  const Program second = value_program("0.375");
  EXPECT_EQ(compiled(), 1u);
  EXPECT_EQ(reused(), 1u);
  EXPECT_NE(first.id(), second.id());  // each call owns its own program
  EXPECT_EQ(drawn_value(first), 0.375f);
  EXPECT_EQ(drawn_value(second), 0.375f);
  // Another define is another program.
  const Program other = value_program("0.25");
  EXPECT_EQ(compiled(), 2u);
  EXPECT_EQ(drawn_value(other), 0.25f);
}

TEST_F(ProgramCacheTest, ABinaryTheDriverRefusesIsCompiledAgain) {
  const Program first = value_program("0.125");
  const std::string key = program_cache_key({{GL_VERTEX_SHADER, "shaders/fullscreen.vert"},
                                             {GL_FRAGMENT_SHADER, "tests/shaders/defined_value.frag"}},
                                            {{"VALUE", "0.125"}});
  ASSERT_TRUE(ProgramCache::instance().replace_binary_for_testing(key, std::vector<uint8_t>(64, 0xA5)));
  const Program second = value_program("0.125");
  EXPECT_EQ(compiled(), 2u);
  EXPECT_EQ(reused(), 0u);
  EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));  // the refusal left no error behind
  EXPECT_EQ(drawn_value(second), 0.125f);
  // The fresh binary replaced the refused one.
  const Program third = value_program("0.125");
  EXPECT_EQ(reused(), 1u);
  EXPECT_EQ(drawn_value(third), 0.125f);
}

TEST_F(ProgramCacheTest, OffCompilesEveryTime) {
  setenv("OIT_PROGRAM_CACHE", "off", 1);
  const Program first = value_program("0.5");
  const Program second = value_program("0.5");
  unsetenv("OIT_PROGRAM_CACHE");
  EXPECT_EQ(compiled(), 2u);
  EXPECT_EQ(reused(), 0u);
  EXPECT_EQ(drawn_value(second), 0.5f);
}

// Two runs of one technique in one harness: the second builds every program
// from the binaries of the first, compiles nothing, and renders the same image.
void expect_second_run_reuses(const std::string& technique) {
  RunSpec spec = test::one_frame(technique, {}, "quads", {{"layers", "4"}, {"objects", "2"}}, 24);
  spec.height = 16;
  const ProgramCacheStats start = ProgramCache::instance().stats();
  const RunResult first = test::harness().run(spec);
  ASSERT_EQ(first.status, RunStatus::ok) << first.message;
  const ProgramCacheStats middle = ProgramCache::instance().stats();
  const RunResult second = test::harness().run(spec);
  ASSERT_EQ(second.status, RunStatus::ok) << second.message;
  const ProgramCacheStats end = ProgramCache::instance().stats();
  EXPECT_GT(middle.compiled, start.compiled) << technique << ": the first run compiled nothing";
  EXPECT_EQ(end.compiled, middle.compiled) << technique << ": the second run compiled again";
  EXPECT_GT(end.reused, middle.reused) << technique;
  ASSERT_EQ(first.image.rgba.size(), second.image.rgba.size());
  size_t differing = 0;  // bit patterns, so even NaNs must match
  for (size_t i = 0; i < first.image.rgba.size(); ++i)
    differing += std::bit_cast<uint32_t>(first.image.rgba[i]) != std::bit_cast<uint32_t>(second.image.rgba[i]);
  EXPECT_EQ(differing, 0u) << technique << ": the program from the binary renders differently";
}

TEST_F(ProgramCacheTest, SecondRunOfBucketedKbufferCompilesNothingAndRendersTheSameImage) {
  expect_second_run_reuses("bucketed_kbuffer");
}

TEST_F(ProgramCacheTest, SecondRunOfIllustrationBufferCompilesNothingAndRendersTheSameImage) {
  expect_second_run_reuses("illustration_buffer");
}

}  // namespace
}  // namespace oit
