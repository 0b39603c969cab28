// The on-disk reference cache: a second harness reads the reference instead
// of rendering it, gets the identical image, and ignores damaged files.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <tuple>

#include "tests/gl_fixture.h"
#include "tests/oitbench_process.h"

namespace oit {
namespace {

// An empty directory `name` under the build's test output, for one test's cache.
std::string fresh_cache_dir(const std::string& name) {
  const std::string dir = std::string(OIT_BINARY_DIR) + "/test_output/" + name;
  std::filesystem::remove_all(dir);
  return dir;
}

// The reference the damage tests cache: quads layers=3, 8x8 on black, rendered
// or read by `harness` through `cache`.
Image quads_reference(Harness& harness, const ReferenceCache& cache) {
  harness.set_reference_cache(cache);
  return harness.reference_image("quads", {{"layers", "3"}}, 8, 8, glm::vec3(0.0f));
}

// What the damage tests start from: a cache in the fresh directory `name`
// that holds one entry, the quads reference `good`, stored by a first harness.
struct CacheOfOneEntry {
  explicit CacheOfOneEntry(const std::string& name) : dir(fresh_cache_dir(name)), cache(dir) {
    Harness first(test::gl_context(), builtin_techniques());
    good = quads_reference(first, cache);
    entry = std::filesystem::directory_iterator(dir)->path();
  }
  std::string dir;
  ReferenceCache cache;
  Image good;
  std::filesystem::path entry;
};

TEST(ReferenceCache, SecondHarnessReadsTheIdenticalImageFromDisk) {
  const std::string dir = fresh_cache_dir("reference_cache_test");
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
  const CacheOfOneEntry one("reference_cache_damaged");
  const auto& [dir, cache, good, file] = one;
  ASSERT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 1);
  std::filesystem::resize_file(file, 20);  // truncated
  Harness again(test::gl_context(), builtin_techniques());
  const Image image = quads_reference(again, cache);
  EXPECT_EQ(again.references_rendered(), 1);
  EXPECT_EQ(image.rgba, good.rgba);
  EXPECT_GT(std::filesystem::file_size(file), 20u);  // rewritten whole
}

// A cache entry's damage that keeps its header valid: a flipped payload
// byte, a payload of NaNs; both are caught by the checksum and rendered again.
TEST(ReferenceCache, ChecksumMismatchOrNonFinitePayloadIsRenderedAgain) {
  const CacheOfOneEntry one("reference_cache_checksum");
  const auto& [dir, cache, good, file] = one;
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
    EXPECT_EQ(quads_reference(again, cache).rgba, good.rgba);
    EXPECT_EQ(again.references_rendered(), 1);
    EXPECT_EQ(again.references_loaded(), 0);
    // Rewritten whole: the next harness reads it.
    Harness next(test::gl_context(), builtin_techniques());
    EXPECT_EQ(quads_reference(next, cache).rgba, good.rgba);
    EXPECT_EQ(next.references_loaded(), 1);
  }
}

TEST(ReferenceCache, AnImageHoldingNanIsNeverServedEvenWithAMatchingChecksum) {
  const std::string dir = fresh_cache_dir("reference_cache_nan");
  const ReferenceCache cache(dir);
  Image image{2, 2, std::vector<float>(16, 0.5f)};
  cache.store("key", image);
  ASSERT_TRUE(cache.load("key").has_value());
  EXPECT_EQ(cache.load("key")->rgba, image.rgba);
  image.rgba[5] = std::nanf("");
  cache.store("key", image);  // written with its checksum
  EXPECT_FALSE(cache.load("key").has_value());
}

// ---- entries that are not what they claim: misses, named, never trusted ----

using test::contents_of;

// The bytes of an entry as store() writes them (version 2: magic, key,
// width, height, payload, FNV-1a checksum of everything before it), with
// `payload_bytes` of payload whatever the declared size.
std::string entry_bytes(const std::string& key, int32_t width, int32_t height, size_t payload_bytes) {
  std::string bytes("OITREF2\n", 8);
  const auto put = [&bytes](const auto& value) { bytes.append(reinterpret_cast<const char*>(&value), sizeof value); };
  put(uint32_t(key.size()));
  bytes += key;
  put(width);
  put(height);
  bytes.append(payload_bytes, '\0');
  uint64_t hash = 1469598103934665603ull;
  for (unsigned char c : bytes) hash = (hash ^ c) * 1099511628211ull;
  put(hash);
  return bytes;
}

struct ChildLoad {
  bool exited = false;  // false: killed (the 20 s alarm: it hung)
  int code = -1;        // 0 a miss, 1 a hit, 2 out of memory, 3 another exception
  std::string warnings;
};

// cache.load(key, width, height) in a child process that may not grow by
// more than 256 MiB and is killed after 20 s, so that a hang or a runaway
// allocation fails the test instead of stopping or exhausting the machine.
ChildLoad load_in_child(const ReferenceCache& cache, const std::string& key, int width, int height) {
  const std::string log = cache.directory() + "/../load_" + std::to_string(::getpid()) + ".txt";
  const pid_t child = fork();
  if (child == 0) {
    if (!std::freopen(log.c_str(), "w", stderr)) _exit(4);
    long pages = 0;
    std::ifstream("/proc/self/statm") >> pages;
    const rlim_t allowance = rlim_t(pages) * rlim_t(sysconf(_SC_PAGESIZE)) + (rlim_t(256) << 20);
    const rlimit limit{allowance, allowance};
    setrlimit(RLIMIT_AS, &limit);
    alarm(20);
    try {
      const bool hit = cache.load(key, width, height).has_value();
      std::fflush(stderr);
      _exit(hit ? 1 : 0);
    } catch (const std::bad_alloc&) {
      _exit(2);
    } catch (...) {
      _exit(3);
    }
  }
  int status = 0;
  waitpid(child, &status, 0);
  ChildLoad result;
  result.exited = WIFEXITED(status);
  result.code = result.exited ? WEXITSTATUS(status) : -1;
  result.warnings = contents_of(log);
  return result;
}

// A FIFO in place of an entry hung the reader; a link to /dev/zero read until
// bad_alloc; a directory was a silent miss that could never be replaced; a
// 4 KB entry whose header claims 16384x16384 allocated 4 GiB before its size
// was checked. Each is now a miss with a warning naming the file.
TEST(ReferenceCache, EntriesThatAreNotRegularFilesOrClaimTooMuchAreMissesNamedInAWarning) {
  const std::string dir = fresh_cache_dir("reference_cache_kinds/entries");
  std::filesystem::create_directories(dir);
  const ReferenceCache cache(dir);
  const std::string key = "scene|8x8|0,0,0", path = cache.path_for(key);
  const std::vector<std::tuple<std::string, std::function<void()>, std::string>> cases = {
      {"FIFO", [&] { ASSERT_EQ(mkfifo(path.c_str(), 0600), 0); }, "is a FIFO, not a regular file"},
      {"link to /dev/zero", [&] { std::filesystem::create_symlink("/dev/zero", path); },
       "is a character device, not a regular file"},
      {"directory", [&] { std::filesystem::create_directory(path); }, "is a directory, not a regular file"},
      {"4 KB claiming 16384x16384", [&] { std::ofstream(path, std::ios::binary) << entry_bytes(key, 16384, 16384, 4096); },
       "does not fit the 16384x16384 image its header declares"},
      {"another format", [&] { std::ofstream(path, std::ios::binary) << std::string(4096, 'x'); },
       "is not an entry of this version of the cache"},
  };
  for (const auto& [what, make, problem] : cases) {
    std::filesystem::remove_all(path);
    make();
    const ChildLoad load = load_in_child(cache, key, 8, 8);
    EXPECT_TRUE(load.exited) << what << ": the load hung";
    EXPECT_EQ(load.code, 0) << what << " (2: out of memory)";
    EXPECT_NE(load.warnings.find(path), std::string::npos) << what << ": " << load.warnings;
    EXPECT_NE(load.warnings.find(problem), std::string::npos) << what << ": " << load.warnings;
  }
  // No entry at all is the ordinary miss: nothing to say.
  std::filesystem::remove_all(path);
  const ChildLoad missing = load_in_child(cache, key, 8, 8);
  EXPECT_EQ(missing.code, 0);
  EXPECT_EQ(missing.warnings, "");
}

// A whole, checksum-valid entry of another image size is a miss (the key
// says the size, so only a foreign or hand-made file holds one).
TEST(ReferenceCache, AnEntryOfAnotherImageSizeIsAMiss) {
  const std::string dir = fresh_cache_dir("reference_cache_size");
  const ReferenceCache cache(dir);
  cache.store("key", Image{4, 4, std::vector<float>(64, 0.25f)});
  testing::internal::CaptureStderr();
  EXPECT_FALSE(cache.load("key", 8, 8).has_value());
  const std::string warnings = testing::internal::GetCapturedStderr();
  EXPECT_NE(warnings.find("holds a 4x4 image where 8x8 is needed"), std::string::npos) << warnings;
  EXPECT_TRUE(cache.load("key", 4, 4).has_value());
}

// A directory in the way: rendered every time, with a warning, never stored.
TEST(ReferenceCache, ADirectoryInPlaceOfAnEntryIsRenderedAndLeftWithAWarning) {
  const CacheOfOneEntry one("reference_cache_directory");
  const auto& [dir, cache, good, entry] = one;
  std::filesystem::remove(entry);
  std::filesystem::create_directory(entry);
  Harness again(test::gl_context(), builtin_techniques());
  testing::internal::CaptureStderr();
  EXPECT_EQ(quads_reference(again, cache).rgba, good.rgba);
  const std::string warnings = testing::internal::GetCapturedStderr();
  EXPECT_EQ(again.references_rendered(), 1);
  EXPECT_NE(warnings.find(entry.string() + ": is a directory, not a regular file"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("reference cache not written"), std::string::npos) << warnings;
  EXPECT_TRUE(std::filesystem::is_directory(entry));
}

}  // namespace
}  // namespace oit
