#pragma once
// Reading an input file that must be a regular file. The file is opened
// without blocking and what it is comes from fstat on the opened descriptor,
// so a FIFO (which would block the reader until a writer comes), a device
// (/dev/zero feeds endless bytes) or a directory is refused by what it is,
// never by what reading it does, and nothing can be swapped in between a
// check and the open. Sizes come from the same descriptor, so a caller can
// check what a header declares against the file's length before it
// allocates anything.
#include <sys/types.h>

#include <cstdint>
#include <string>

namespace oit {

// What a file of stat mode `mode` is, for messages: "" for a regular file,
// else "a directory", "a FIFO", "a character device", ... (links followed).
std::string file_kind(mode_t mode);

// The largest scene file (a mesh, a glTF or a buffer it names) read.
inline constexpr uint64_t kMaxSceneFileBytes = uint64_t(2) << 30;

class RegularFile {
 public:
  // Throws std::invalid_argument "<path>: <problem>": it does not exist, it
  // cannot be opened (the system's reason), or it is not a regular file
  // ("is a directory, not a regular file", links followed).
  explicit RegularFile(const std::string& path);
  ~RegularFile();
  RegularFile(const RegularFile&) = delete;
  RegularFile& operator=(const RegularFile&) = delete;

  uint64_t size() const { return size_; }
  // Exactly `length` bytes from `offset`; throws naming the file when they
  // are not all there (the file was cut while being read) or reading fails.
  std::string read(uint64_t offset, uint64_t length) const;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
  uint64_t size_ = 0;
};

// The whole of `path`, a regular file of at most `max_bytes` (larger:
// std::invalid_argument naming the file, its size and the limit).
std::string read_regular_file(const std::string& path, uint64_t max_bytes);

}  // namespace oit
