#pragma once
// Every file oitbench writes goes through here, so that no result is lost or
// silently cut short (a full disk, a link to a device that refuses writes):
// every write and the close are checked, and a failure is an exception
// naming the file and the system's reason.
//  - Whole files (images, cache entries) are written to a temporary file in
//    the destination's directory, synced and renamed into place: the
//    destination holds the old content or the whole new one, never a part.
//    A SIGTERM or SIGINT while such a temporary file exists removes it
//    before the process ends; one left by a process killed harder (SIGKILL,
//    a power cut) is removed by the next write to the same destination once
//    the process that made it is gone.
//  - Files many processes append to (result CSVs) are locked with flock and
//    appended one unit at a time; a failed append is cut back off.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace oit {

// `bytes` as the whole new content of `path`; parent directories are
// created. A link is followed (the file it names is replaced, the link
// kept); a destination that exists and is not a regular file (a device, a
// FIFO, a directory) is refused. On failure `path` is left as it was, no
// temporary file remains, and the exception names `path`.
void write_file_atomically(const std::string& path, std::string_view bytes);
// The same for a file that must not exist yet: false (and nothing written)
// when `path` exists, whatever it is; never replaces anything.
bool write_new_file_atomically(const std::string& path, std::string_view bytes);

// One output of a command: the option that names it ("--csv") and its path.
struct NamedOutput {
  std::string option;
  std::string path;
};
// Throws std::invalid_argument naming both options and the path when two
// of `outputs` are the same file (one would overwrite the other): the same
// inode when both exist, else the same absolute path once normalised (".."
// and links resolved as far as the path exists). Empty paths (options not
// given) are left out. Called before anything runs or is written.
void check_distinct_outputs(const std::vector<NamedOutput>& outputs);

// All `size` bytes to `fd` (short writes and EINTR retried); throws naming
// `path` with the system's reason (e.g. "No space left on device").
void write_all(int fd, const void* data, size_t size, const std::string& path);

// Throws naming `path` and `what` ("scene file", "parameter ...") unless
// `path` names a regular file (links followed): a FIFO would block the
// reader forever, a device would feed it endless bytes.
void require_regular_file(const std::string& path, const std::string& what);

// A file shared by appending processes, opened for reading and appending
// and created when missing. Appends and repairs hold the exclusive lock,
// reads the shared one (flock: advisory, released when the process ends).
class SharedAppendFile {
 public:
  explicit SharedAppendFile(std::string path);
  ~SharedAppendFile();
  SharedAppendFile(const SharedAppendFile&) = delete;
  SharedAppendFile& operator=(const SharedAppendFile&) = delete;

  class Lock {
   public:
    Lock(int fd, bool exclusive, const std::string& path);
    ~Lock();
    Lock(const Lock&) = delete;
    Lock& operator=(const Lock&) = delete;

   private:
    int fd_;
  };
  Lock lock_exclusive() const { return Lock(fd_, true, path_); }
  Lock lock_shared() const { return Lock(fd_, false, path_); }

  // `text` at the end in one write(2), then synced; call under the
  // exclusive lock. When the write fails part way (a full disk), the file
  // is cut back to its size before, so it never keeps part of `text`.
  void append(std::string_view text);
  std::string read_all() const;
  uint64_t size() const;
  // Cuts the file to `size` bytes (repairing a torn end); exclusive lock.
  void truncate(uint64_t size);
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace oit
