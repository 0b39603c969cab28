#include "scenes/regular_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace oit {
std::string file_kind(mode_t mode) {
  if (S_ISREG(mode)) return "";
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "a special file";
}

RegularFile::RegularFile(const std::string& path) : path_(path) {
  // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer.
  fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) {
    const int error = errno;
    if (error == ENOENT) throw std::invalid_argument(path + ": does not exist");
    throw std::invalid_argument(path + ": cannot be opened: " + std::strerror(error));
  }
  struct stat info{};
  if (::fstat(fd_, &info) != 0) {
    const int error = errno;
    ::close(fd_);
    throw std::invalid_argument(path + ": cannot be examined: " + std::strerror(error));
  }
  if (const std::string kind = file_kind(info.st_mode); !kind.empty()) {
    ::close(fd_);
    throw std::invalid_argument(path + ": is " + kind + ", not a regular file");
  }
  size_ = uint64_t(info.st_size);
}

RegularFile::~RegularFile() { ::close(fd_); }

std::string RegularFile::read(uint64_t offset, uint64_t length) const {
  if (offset > size_ || length > size_ - offset)
    throw std::invalid_argument(path_ + ": " + std::to_string(length) + " bytes at offset " + std::to_string(offset) +
                                " are past its end (" + std::to_string(size_) + " bytes)");
  std::string bytes(size_t(length), '\0');
  for (uint64_t done = 0; done < length;) {
    const ssize_t got = ::pread(fd_, bytes.data() + done, size_t(length - done), off_t(offset + done));
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw std::invalid_argument(path_ + ": cannot be read: " + std::strerror(errno));
    if (got == 0) throw std::invalid_argument(path_ + ": became shorter while being read");
    done += uint64_t(got);
  }
  return bytes;
}

std::string read_regular_file(const std::string& path, uint64_t max_bytes) {
  const RegularFile file(path);
  if (file.size() > max_bytes)
    throw std::invalid_argument(path + ": " + std::to_string(file.size()) + " bytes, more than the " +
                                std::to_string(max_bytes) + " a file may have here");
  return file.read(0, file.size());
}

}  // namespace oit
