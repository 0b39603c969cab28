#include "harness/output/output_file.h"

#include <dirent.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <charconv>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <stdexcept>

#include "scenes/regular_file.h"

namespace oit {
namespace {

std::runtime_error failure(const std::string& what, const std::string& path, int error) {
  return std::runtime_error(what + " '" + path + "': " + std::strerror(error));
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

// The temporary files being written, for the SIGTERM/SIGINT handler: fixed
// slots holding fixed-size paths, so that the handler reads them without
// allocating or locking. A slot is free, being filled, or ready.
enum SlotState : int { kFree, kFilling, kReady };
struct TemporarySlot {
  std::atomic<int> state{kFree};
  char path[PATH_MAX];
};
std::array<TemporarySlot, 64> g_temporaries;
struct sigaction g_previous_action[NSIG];

// Removes every temporary file being written, then lets the signal do what
// it did before (end the process, or the handler installed before ours).
// unlink, sigaction and raise are async-signal-safe.
extern "C" void remove_temporaries_and_reraise(int signal) {
  for (TemporarySlot& slot : g_temporaries)
    if (slot.state.load(std::memory_order_acquire) == kReady) ::unlink(slot.path);
  ::sigaction(signal, &g_previous_action[signal], nullptr);
  ::raise(signal);
}

// Once per process, before the first temporary file exists. A signal the
// process ignores (nohup) stays ignored: removing a file that the write
// then renames would lose the output.
void install_temporary_file_handlers() {
  static std::once_flag installed;
  std::call_once(installed, [] {
    for (int signal : {SIGTERM, SIGINT}) {
      if (::sigaction(signal, nullptr, &g_previous_action[signal]) != 0 ||
          g_previous_action[signal].sa_handler == SIG_IGN)
        continue;
      struct sigaction action{};
      action.sa_handler = remove_temporaries_and_reraise;
      sigemptyset(&action.sa_mask);
      sigaddset(&action.sa_mask, SIGTERM);
      sigaddset(&action.sa_mask, SIGINT);
      ::sigaction(signal, &action, nullptr);
    }
  });
}

// A temporary file's path in a slot while it exists; with every slot taken
// (more writes at once than slots) it is not registered, and the sweep of
// the next write to the same destination removes it if it is left over.
class RegisteredTemporary {
 public:
  RegisteredTemporary() { install_temporary_file_handlers(); }
  ~RegisteredTemporary() {
    if (slot_) slot_->state.store(kFree, std::memory_order_release);
  }
  RegisteredTemporary(const RegisteredTemporary&) = delete;
  RegisteredTemporary& operator=(const RegisteredTemporary&) = delete;

  // Called with the path just created, before anything is written to it.
  void hold(const std::string& path) {
    if (slot_ || path.size() >= PATH_MAX) return;
    for (TemporarySlot& slot : g_temporaries) {
      int expected = kFree;
      if (!slot.state.compare_exchange_strong(expected, kFilling)) continue;
      std::memcpy(slot.path, path.c_str(), path.size() + 1);
      slot.state.store(kReady, std::memory_order_release);
      slot_ = &slot;
      return;
    }
  }

 private:
  TemporarySlot* slot_ = nullptr;
};

std::string temporary_prefix(const std::filesystem::path& target) {
  return "." + target.filename().string() + ".tmp-";
}

// Temporary files of `target` left by processes that no longer run (killed
// by a signal no handler sees): ".<name>.tmp-<pid>-<n>" with <pid> gone.
// Those of running processes, this one's included, are theirs to finish.
void remove_stale_temporaries(const std::filesystem::path& target) {
  const std::string directory = target.has_parent_path() ? target.parent_path().string() : ".";
  const std::string prefix = temporary_prefix(target);
  DIR* listing = ::opendir(directory.c_str());
  if (!listing) return;  // the write itself reports a directory it cannot use
  while (const dirent* entry = ::readdir(listing)) {
    const std::string_view name(entry->d_name);
    if (name.substr(0, prefix.size()) != prefix) continue;
    const std::string_view rest = name.substr(prefix.size());
    const size_t dash = rest.find('-');
    if (dash == 0 || dash == std::string_view::npos || rest.find_first_not_of("0123456789") != dash ||
        dash + 1 == rest.size() || rest.find_first_not_of("0123456789", dash + 1) != std::string_view::npos)
      continue;
    pid_t pid = 0;
    if (std::from_chars(rest.data(), rest.data() + dash, pid).ec != std::errc()) continue;  // not a pid
    if (pid == ::getpid() || pid <= 0 || ::kill(pid, 0) == 0 || errno != ESRCH) continue;
    ::unlink((directory + "/" + std::string(name)).c_str());
  }
  ::closedir(listing);
}

// Opens a new, unique temporary file beside `target` (hidden, so globs of
// the outputs never see it). Mode 0666 less the umask, as for any new file.
int open_temporary(const std::filesystem::path& target, std::string& temporary) {
  static std::atomic<unsigned> counter{0};
  for (int attempt = 0; attempt < 100; ++attempt) {
    temporary = (target.parent_path() / (temporary_prefix(target) + std::to_string(::getpid()) + "-" +
                                         std::to_string(counter++)))
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

// Whether `a` and `b` name one file: by inode when both exist (links, hard
// links and "dir/../x" all found), else by the normalised absolute path
// (one existing and the other not: two files).
bool same_file(const std::string& a, const std::string& b) {
  struct stat info_a{}, info_b{};
  const bool a_exists = ::stat(a.c_str(), &info_a) == 0, b_exists = ::stat(b.c_str(), &info_b) == 0;
  if (a_exists && b_exists) return info_a.st_dev == info_b.st_dev && info_a.st_ino == info_b.st_ino;
  if (a_exists || b_exists) return false;
  const auto normalised = [](const std::string& path) {
    std::error_code error;
    const std::filesystem::path absolute = std::filesystem::absolute(path, error);
    const std::filesystem::path resolved = std::filesystem::weakly_canonical(absolute, error);
    return error ? absolute.lexically_normal() : resolved;
  };
  return normalised(a) == normalised(b);
}

}  // namespace

void check_distinct_outputs(const std::vector<NamedOutput>& outputs) {
  for (size_t i = 0; i < outputs.size(); ++i) {
    for (size_t j = i + 1; j < outputs.size(); ++j) {
      const NamedOutput &first = outputs[i], &second = outputs[j];
      if (first.path.empty() || second.path.empty() || !same_file(first.path, second.path)) continue;
      const std::string paths = first.path == second.path ? "both name '" + first.path + "'"
                                                          : "name the same file ('" + first.path + "' and '" +
                                                                second.path + "')";
      throw std::invalid_argument(first.option + " and " + second.option + " " + paths + ": writing " +
                                  second.option + " would replace what " + first.option +
                                  " holds; give each its own path");
    }
  }
}

namespace {

void create_parent_directories(const std::string& path) {
  if (const auto parent = std::filesystem::path(path).parent_path(); !parent.empty()) {
    std::error_code error;
    std::filesystem::create_directories(parent, error);
    if (error) throw std::runtime_error("cannot create the directory of '" + path + "': " + error.message());
  }
}

// `bytes` in a new, synced temporary file beside `target`, held by
// `registration` until the caller has moved it into place; returns its path.
// Leftovers of dead writers of `target` are removed first.
std::string write_temporary(const std::filesystem::path& target, std::string_view bytes, const std::string& path,
                            RegisteredTemporary& registration) {
  remove_stale_temporaries(target);
  std::string temporary;
  const int fd = open_temporary(target, temporary);
  if (fd < 0) throw failure("cannot create a temporary file to write", path, errno);
  registration.hold(temporary);
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
  RegisteredTemporary registration;
  const std::string temporary = write_temporary(target, bytes, path, registration);
  if (::rename(temporary.c_str(), target.c_str()) != 0) {
    const int error = errno;
    ::unlink(temporary.c_str());
    throw failure("cannot move the new file into place at", path, error);
  }
}

bool write_new_file_atomically(const std::string& path, std::string_view bytes) {
  create_parent_directories(path);
  RegisteredTemporary registration;
  const std::string temporary = write_temporary(std::filesystem::path(path), bytes, path, registration);
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
