// The on-disk reference cache: a second harness reads the reference instead
// of rendering it, gets the identical image, and ignores damaged files.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

#include "tests/gl_fixture.h"

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

// A cache entry's damage that keeps its header valid: a flipped payload
// byte, a payload of NaNs; both are caught by the checksum and rendered again.
TEST(ReferenceCache, ChecksumMismatchOrNonFinitePayloadIsRenderedAgain) {
  const std::string dir = std::string(OIT_BINARY_DIR) + "/test_output/reference_cache_checksum";
  std::filesystem::remove_all(dir);
  const ReferenceCache cache(dir);
  const RawParams scene = {{"layers", "3"}};
  Harness harness(test::gl_context(), builtin_techniques());
  harness.set_reference_cache(cache);
  const Image good = harness.reference_image("quads", scene, 8, 8, glm::vec3(0.0f));
  const auto file = std::filesystem::directory_iterator(dir)->path();
  const auto size = std::filesystem::file_size(file);
  const size_t payload = 8 * 8 * 4 * sizeof(float), checksum = 8;
  const std::vector<std::function<void(std::fstream&)>> damages = {
      [&](std::fstream& io) {  // one bit of one pixel
        io.seekg(std::streamoff(size - checksum - 5));
        const char byte = char(io.get() ^ 0x01);
        io.seekp(std::streamoff(size - checksum - 5));
        io.put(byte);
      },
      [&](std::fstream& io) {  // every channel NaN, header untouched
        const std::vector<float> nans(payload / sizeof(float), std::nanf(""));
        io.seekp(std::streamoff(size - checksum - payload));
        io.write(reinterpret_cast<const char*>(nans.data()), std::streamsize(payload));
      }};
  for (const auto& damage : damages) {
    {
      std::fstream io(file, std::ios::in | std::ios::out | std::ios::binary);
      damage(io);
    }
    ASSERT_EQ(std::filesystem::file_size(file), size);
    Harness again(test::gl_context(), builtin_techniques());
    again.set_reference_cache(cache);
    EXPECT_EQ(again.reference_image("quads", scene, 8, 8, glm::vec3(0.0f)).rgba, good.rgba);
    EXPECT_EQ(again.references_rendered(), 1);
    EXPECT_EQ(again.references_loaded(), 0);
    // Rewritten whole: the next harness reads it.
    Harness next(test::gl_context(), builtin_techniques());
    next.set_reference_cache(cache);
    EXPECT_EQ(next.reference_image("quads", scene, 8, 8, glm::vec3(0.0f)).rgba, good.rgba);
    EXPECT_EQ(next.references_loaded(), 1);
  }
}

TEST(ReferenceCache, AnImageHoldingNanIsNeverServedEvenWithAMatchingChecksum) {
  const std::string dir = std::string(OIT_BINARY_DIR) + "/test_output/reference_cache_nan";
  std::filesystem::remove_all(dir);
  const ReferenceCache cache(dir);
  Image image{2, 2, std::vector<float>(16, 0.5f)};
  cache.store("key", image);
  ASSERT_TRUE(cache.load("key").has_value());
  EXPECT_EQ(cache.load("key")->rgba, image.rgba);
  image.rgba[5] = std::nanf("");
  cache.store("key", image);  // written with its checksum
  EXPECT_FALSE(cache.load("key").has_value());
}

}  // namespace
}  // namespace oit
