#include "io/child_process.h"

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <new>
#include <stdexcept>

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace ddish::io {

namespace {

constexpr char kAnswer = 'O';
constexpr char kError = 'E';

void write_all(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;  // the parent is gone or stopped reading: nobody to tell
    data += n;
    size -= static_cast<std::size_t>(n);
  }
}

[[noreturn]] void run_child(int fd, pid_t parent, const std::function<std::string()>& work) {
  std::signal(SIGINT, SIG_IGN);
  std::signal(SIGTERM, SIG_IGN);
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(1);  // the parent died before the line above
  std::string message;
  try {
    message = kAnswer + work();
  } catch (const std::bad_alloc&) {
    message = std::string(1, kError) + "out of memory";
  } catch (const std::exception& e) {
    message = kError + std::string(e.what());
  } catch (...) {
    message = std::string(1, kError) + "an unknown exception";
  }
  write_all(fd, message.data(), message.size());
  // _exit: no atexit handlers and no destructors of state that belongs to the parent.
  ::_exit(0);
}

std::string how_it_ended(int status) {
  if (WIFSIGNALED(status))
    return "killed by signal " + std::to_string(WTERMSIG(status)) + " (" + strsignal(WTERMSIG(status)) + ")";
  if (WIFEXITED(status)) return "exited with status " + std::to_string(WEXITSTATUS(status)) + " without an answer";
  return "ended without an answer";
}

}  // namespace

ChildOutcome run_in_child(const std::function<std::string()>& work, std::chrono::milliseconds limit) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    throw std::runtime_error(std::string("cannot create a pipe for a child process: ") + std::strerror(errno));
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int err = errno;
    ::close(fds[0]);
    ::close(fds[1]);
    throw std::runtime_error(std::string("cannot start a child process: ") + std::strerror(err));
  }
  if (pid == 0) {
    ::close(fds[0]);
    run_child(fds[1], parent, work);
  }
  ::close(fds[1]);

  const auto deadline = std::chrono::steady_clock::now() + limit;
  std::string received;
  bool timed_out = false;
  char chunk[1 << 16];
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) continue;  // no data yet: the loop re-checks the deadline
    const ssize_t n = ::read(fds[0], chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // end of file: the child has answered (or died)
    received.append(chunk, static_cast<std::size_t>(n));
  }
  ::close(fds[0]);
  if (timed_out) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }

  ChildOutcome out;
  if (timed_out) {
    out.status = ChildOutcome::Status::kTimedOut;
  } else if (received.empty() || !(WIFEXITED(status) && WEXITSTATUS(status) == 0)) {
    out.status = ChildOutcome::Status::kCrashed;
    out.bytes = how_it_ended(status);
  } else {
    out.status = received[0] == kAnswer ? ChildOutcome::Status::kOk : ChildOutcome::Status::kFailed;
    out.bytes = received.substr(1);
  }
  return out;
}

}  // namespace ddish::io
