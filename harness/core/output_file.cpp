#include "harness/core/output_file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace oit {
namespace {

std::runtime_error failure(const std::string& what, const std::string& path, int error) {
  return std::runtime_error(what + " '" + path + "': " + std::strerror(error));
}

std::string file_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Where the new content goes: the file a link names (so the link stays), or
// `path` itself when nothing is there yet.
std::filesystem::path destination_of(const std::string& path) {
  struct stat info{};
  if (::stat(path.c_str(), &info) != 0) {
    if (errno == ENOENT) return path;
    throw failure("cannot write", path, errno);
  }
  if (!S_ISREG(info.st_mode)) {
    throw std::runtime_error("cannot write '" + path + "': it is " + file_kind(info.st_mode) +
                             (std::filesystem::is_symlink(path) ? " (through a link)" : "") +
                             ", not a regular file; choose a file path");
  }
  return std::filesystem::canonical(path);
}

// Opens a new, unique temporary file beside `target` (hidden, so globs of
// the outputs never see it). Mode 0666 less the umask, as for any new file.
int open_temporary(const std::filesystem::path& target, std::string& temporary) {
  static std::atomic<unsigned> counter{0};
  for (int attempt = 0; attempt < 100; ++attempt) {
    temporary = (target.parent_path() / ("." + target.filename().string() + ".tmp-" + std::to_string(::getpid()) +
                                         "-" + std::to_string(counter++)))
                    .string();
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0 || errno != EEXIST) return fd;
  }
  errno = EEXIST;
  return -1;
}

}  // namespace

void write_all(int fd, const void* data, size_t size, const std::string& path) {
  const char* bytes = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t written = ::write(fd, bytes, size);
    if (written < 0 && errno == EINTR) continue;
    if (written < 0) throw failure("failed writing", path, errno);
    if (written == 0) throw failure("failed writing", path, EIO);
    bytes += written;
    size -= size_t(written);
  }
}

void require_regular_file(const std::string& path, const std::string& what) {
  struct stat info{};
  if (::stat(path.c_str(), &info) != 0) throw failure("cannot open " + what, path, errno);
  if (!S_ISREG(info.st_mode))
    throw std::runtime_error(what + " '" + path + "' is " + file_kind(info.st_mode) + ", not a regular file");
}

namespace {

void create_parent_directories(const std::string& path) {
  if (const auto parent = std::filesystem::path(path).parent_path(); !parent.empty()) {
    std::error_code error;
    std::filesystem::create_directories(parent, error);
    if (error) throw std::runtime_error("cannot create the directory of '" + path + "': " + error.message());
  }
}

// `bytes` in a new, synced temporary file beside `target`; returns its path.
std::string write_temporary(const std::filesystem::path& target, std::string_view bytes, const std::string& path) {
  std::string temporary;
  const int fd = open_temporary(target, temporary);
  if (fd < 0) throw failure("cannot create a temporary file to write", path, errno);
  bool closed = false;
  try {
    write_all(fd, bytes.data(), bytes.size(), path);
    if (::fsync(fd) != 0) throw failure("failed writing", path, errno);
    closed = true;
    if (::close(fd) != 0) throw failure("failed writing", path, errno);
  } catch (...) {
    if (!closed) ::close(fd);
    ::unlink(temporary.c_str());
    throw;
  }
  return temporary;
}

}  // namespace

void write_file_atomically(const std::string& path, std::string_view bytes) {
  create_parent_directories(path);
  const std::filesystem::path target = destination_of(path);
  const std::string temporary = write_temporary(target, bytes, path);
  if (::rename(temporary.c_str(), target.c_str()) != 0) {
    const int error = errno;
    ::unlink(temporary.c_str());
    throw failure("cannot move the new file into place at", path, error);
  }
}

bool write_new_file_atomically(const std::string& path, std::string_view bytes) {
  create_parent_directories(path);
  const std::string temporary = write_temporary(std::filesystem::path(path), bytes, path);
  // link(2), unlike rename(2), fails when the name exists: no check-then-write
  // race with another process writing the same name.
  const int linked = ::link(temporary.c_str(), path.c_str());
  const int error = errno;
  ::unlink(temporary.c_str());
  if (linked == 0) return true;
  if (error == EEXIST) return false;
  throw failure("cannot move the new file into place at", path, error);
}

SharedAppendFile::SharedAppendFile(std::string path) : path_(std::move(path)) {
  if (const auto parent = std::filesystem::path(path_).parent_path(); !parent.empty()) {
    std::error_code error;
    std::filesystem::create_directories(parent, error);
    if (error) throw std::runtime_error("cannot create the directory of '" + path_ + "': " + error.message());
  }
  // O_NONBLOCK: opening a FIFO must not wait for a writer; it is refused below.
  fd_ = ::open(path_.c_str(), O_RDWR | O_APPEND | O_CREAT | O_CLOEXEC | O_NONBLOCK, 0666);
  if (fd_ < 0) throw failure("cannot open", path_, errno);
  struct stat info{};
  if (::fstat(fd_, &info) != 0 || !S_ISREG(info.st_mode)) {
    ::close(fd_);
    throw std::runtime_error("cannot append to '" + path_ + "': it is " + file_kind(info.st_mode) +
                             ", not a regular file");
  }
  ::fcntl(fd_, F_SETFL, O_APPEND);  // back to blocking
}

SharedAppendFile::~SharedAppendFile() {
  if (fd_ >= 0) ::close(fd_);
}

SharedAppendFile::Lock::Lock(int fd, bool exclusive, const std::string& path) : fd_(fd) {
  while (::flock(fd_, exclusive ? LOCK_EX : LOCK_SH) != 0) {
    if (errno != EINTR) throw failure("cannot lock", path, errno);
  }
}

SharedAppendFile::Lock::~Lock() { ::flock(fd_, LOCK_UN); }

uint64_t SharedAppendFile::size() const {
  struct stat info{};
  if (::fstat(fd_, &info) != 0) throw failure("cannot read the size of", path_, errno);
  return uint64_t(info.st_size);
}

void SharedAppendFile::append(std::string_view text) {
  const uint64_t before = size();
  try {
    write_all(fd_, text.data(), text.size(), path_);
    if (::fdatasync(fd_) != 0) throw failure("failed writing", path_, errno);
  } catch (const std::exception& e) {
    // Nothing of a failed unit stays; if even that fails, say so.
    if (::ftruncate(fd_, off_t(before)) != 0)
      throw std::runtime_error(std::string(e.what()) + "; cutting the partial write back off failed too (" +
                               std::strerror(errno) + "): the file's end is torn");
    throw;
  }
}

std::string SharedAppendFile::read_all() const {
  std::string text;
  char block[1 << 16];
  for (off_t offset = 0;;) {
    const ssize_t got = ::pread(fd_, block, sizeof block, offset);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw failure("cannot read", path_, errno);
    if (got == 0) return text;
    text.append(block, size_t(got));
    offset += got;
  }
}

void SharedAppendFile::truncate(uint64_t size) {
  if (::ftruncate(fd_, off_t(size)) != 0) throw failure("cannot cut back", path_, errno);
  if (::fdatasync(fd_) != 0) throw failure("failed writing", path_, errno);
}

}  // namespace oit
