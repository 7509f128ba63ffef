#include "io/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <climits>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

namespace ddish::io {

namespace fs = std::filesystem;

namespace {

std::string errno_text(int error) { return std::error_code(error, std::generic_category()).message(); }

// A write in progress, as the signal handler sees it: it unlinks `path` only in state kReady,
// so it never reads a path that is being copied in.
struct TrackedWrite {
  enum State : int { kFree = 0, kFilling = 1, kReady = 2 };
  std::atomic<int> state{kFree};
  char path[PATH_MAX] = {};
};
static_assert(std::atomic<int>::is_always_lock_free, "signal handlers need lock-free atomics");

// Constant-initialized (no guard a signal handler could run into).
std::array<TrackedWrite, kTrackedWrites> g_tracked_writes;

// Registers a temporary for remove_partial_files while it exists. Beyond kTrackedWrites
// concurrent writes a temporary is simply not registered: it is still removed on every error,
// only an abort in the middle of that write could leave it behind.
class Registration {
 public:
  explicit Registration(const std::string& path) {
    if (path.size() >= PATH_MAX) return;
    for (TrackedWrite& w : g_tracked_writes) {
      int expected = TrackedWrite::kFree;
      if (!w.state.compare_exchange_strong(expected, TrackedWrite::kFilling)) continue;
      std::memcpy(w.path, path.c_str(), path.size() + 1);
      w.state.store(TrackedWrite::kReady);
      slot_ = &w;
      return;
    }
  }
  ~Registration() {
    if (slot_) slot_->state.store(TrackedWrite::kFree);
  }
  Registration(const Registration&) = delete;
  Registration& operator=(const Registration&) = delete;

 private:
  TrackedWrite* slot_ = nullptr;
};

fs::path temporary_for(const fs::path& path) {
  static std::atomic<unsigned> counter{0};
  // Appended piece by piece: GCC 12 at -O3 warns (-Wrestrict, a known false positive) on
  // "." + std::string + ... chains, and CI makes warnings errors.
  std::string name = ".";
  name += path.filename().string();
  name += ".ddish-";
  name += std::to_string(::getpid());
  name += '-';
  name += std::to_string(counter.fetch_add(1));
  name += ".part";
  return path.parent_path() / name;
}

// Written data reaches the disk before the rename makes it visible under the real name (and a
// full disk that only shows at write-back is reported here, not lost).
void sync_file(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw std::runtime_error(errno_text(errno));
  const int rc = ::fsync(fd);
  const int error = errno;
  ::close(fd);
  if (rc != 0) throw std::runtime_error(errno_text(error));
}

void write_all(int fd, std::string_view bytes) {
  while (!bytes.empty()) {
    const ssize_t n = ::write(fd, bytes.data(), bytes.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(errno_text(errno));
    }
    bytes.remove_prefix(static_cast<std::size_t>(n));
  }
}

}  // namespace

void write_atomically(const fs::path& path,
                      const std::function<void(const fs::path& temporary)>& write) {
  if (path.filename().empty()) throw std::runtime_error("cannot write " + path.string() + ": no file name");
  const fs::path temporary = temporary_for(path);
  const Registration registration(temporary.string());
  try {
    write(temporary);
    sync_file(temporary);
    if (::rename(temporary.c_str(), path.c_str()) != 0) throw std::runtime_error(errno_text(errno));
  } catch (const std::exception& e) {
    ::unlink(temporary.c_str());
    throw std::runtime_error("cannot write " + path.string() + ": " + e.what());
  }
}

void write_file_atomically(const fs::path& path, std::string_view bytes) {
  write_atomically(path, [bytes](const fs::path& temporary) {
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) throw std::runtime_error(errno_text(errno));
    try {
      write_all(fd, bytes);
    } catch (...) {
      ::close(fd);
      throw;
    }
    if (::close(fd) != 0) throw std::runtime_error(errno_text(errno));
  });
}

struct AtomicFileWriter::Open {
  fs::path temporary;
  Registration registration;
  int fd = -1;
  explicit Open(fs::path t) : temporary(std::move(t)), registration(temporary.string()) {}
  ~Open() {
    if (fd >= 0) ::close(fd);
    ::unlink(temporary.c_str());  // a no-op once committed (renamed away)
  }
};

AtomicFileWriter::AtomicFileWriter(const fs::path& path) : path_(path) {
  if (path.filename().empty()) throw std::runtime_error("cannot write " + path.string() + ": no file name");
  open_ = std::make_unique<Open>(temporary_for(path));
  open_->fd = ::open(open_->temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (open_->fd < 0) {
    const int error = errno;
    open_.reset();
    throw std::runtime_error("cannot write " + path.string() + ": " + errno_text(error));
  }
}

AtomicFileWriter::~AtomicFileWriter() = default;

void AtomicFileWriter::write(std::string_view bytes) {
  if (!open_) throw std::runtime_error("cannot write " + path_.string() + ": already closed");
  try {
    write_all(open_->fd, bytes);
  } catch (const std::exception& e) {
    open_.reset();
    throw std::runtime_error("cannot write " + path_.string() + ": " + e.what());
  }
}

void AtomicFileWriter::commit() {
  if (!open_) throw std::runtime_error("cannot write " + path_.string() + ": already closed");
  try {
    const int fd = std::exchange(open_->fd, -1);
    const int synced = ::fsync(fd);
    const int sync_error = errno;
    if (::close(fd) != 0 && synced == 0) throw std::runtime_error(errno_text(errno));
    if (synced != 0) throw std::runtime_error(errno_text(sync_error));
    if (::rename(open_->temporary.c_str(), path_.c_str()) != 0) throw std::runtime_error(errno_text(errno));
  } catch (const std::exception& e) {
    open_.reset();
    throw std::runtime_error("cannot write " + path_.string() + ": " + e.what());
  }
  open_.reset();
}

void check_writable_folder(const fs::path& dir) {
  const std::string fail = "cannot write to output folder " + dir.string() + ": ";
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error(fail + ec.message());
  if (!fs::is_directory(dir, ec)) throw std::runtime_error(fail + "not a folder");
  // One byte, so that a full disk shows here and not after the run's work.
  const fs::path probe = dir / (".ddish-write-check-" + std::to_string(::getpid()));
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) throw std::runtime_error(fail + errno_text(errno));
  std::string reason;
  try {
    write_all(fd, "x");
  } catch (const std::exception& e) {
    reason = e.what();
  }
  if (::close(fd) != 0 && reason.empty()) reason = errno_text(errno);
  ::unlink(probe.c_str());
  if (!reason.empty()) throw std::runtime_error(fail + reason);
}

void check_writable_file(const fs::path& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec))
    throw std::runtime_error("cannot write " + path.string() + ": it is a folder");
  const fs::path dir = path.parent_path();
  check_writable_folder(dir.empty() ? fs::path(".") : dir);
}

void remove_partial_files() noexcept {
  for (TrackedWrite& w : g_tracked_writes)
    if (w.state.load() == TrackedWrite::kReady) ::unlink(w.path);
}

}  // namespace ddish::io
