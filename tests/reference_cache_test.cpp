// The on-disk reference cache: a second harness reads the reference instead
// of rendering it, gets the identical image, and ignores damaged files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "gl_fixture.h"

namespace oit {
namespace {

TEST(ReferenceCache, SecondHarnessReadsTheIdenticalImageFromDisk) {
  const std::string dir = std::string(OIT_BINARY_DIR) + "/test_output/reference_cache_test";
  std::filesystem::remove_all(dir);
  const RawParams scene = {{"layers", "6"}};
  Harness first(test::gl_context(), builtin_techniques());
  first.set_reference_cache(ReferenceCache(dir));
  const Image rendered = first.reference_image("quads", scene, 24, 16, glm::vec3(0.1f));
  EXPECT_EQ(first.references_rendered(), 1);
  EXPECT_EQ(first.references_loaded(), 0);

  Harness second(test::gl_context(), builtin_techniques());
  second.set_reference_cache(ReferenceCache(dir));
  const Image loaded = second.reference_image("quads", scene, 24, 16, glm::vec3(0.1f));
  EXPECT_EQ(second.references_rendered(), 0);
  EXPECT_EQ(second.references_loaded(), 1);
  EXPECT_EQ(loaded.width, 24);
  EXPECT_EQ(loaded.rgba, rendered.rgba);

  // Another background is another key.
  second.reference_image("quads", scene, 24, 16, glm::vec3(0.2f));
  EXPECT_EQ(second.references_rendered(), 1);
}

TEST(ReferenceCache, DamagedFileIsAMissAndIsReplaced) {
  const std::string dir = std::string(OIT_BINARY_DIR) + "/test_output/reference_cache_damaged";
  std::filesystem::remove_all(dir);
  const ReferenceCache cache(dir);
  Harness harness(test::gl_context(), builtin_techniques());
  harness.set_reference_cache(cache);
  const Image good = harness.reference_image("quads", {{"layers", "3"}}, 8, 8, glm::vec3(0.0f));
  ASSERT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1);
  const auto file = std::filesystem::directory_iterator(dir)->path();
  std::filesystem::resize_file(file, 20);  // truncated
  Harness again(test::gl_context(), builtin_techniques());
  again.set_reference_cache(cache);
  const Image image = again.reference_image("quads", {{"layers", "3"}}, 8, 8, glm::vec3(0.0f));
  EXPECT_EQ(again.references_rendered(), 1);
  EXPECT_EQ(image.rgba, good.rgba);
  EXPECT_GT(std::filesystem::file_size(file), 20u);  // rewritten whole
}

}  // namespace
}  // namespace oit
