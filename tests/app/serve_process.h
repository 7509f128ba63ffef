// Background ddish processes for the probe-service tests (`serve`, several `view`s): spawned
// with their stdout and stderr in files, killed by their destructors so nothing outlives a test,
// and bounded waits on what they write.
#pragma once

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fcntl.h>
#include <string>
#include <thread>
#include <vector>

#include "cli_runner.h"

extern char** environ;

namespace cli {

// A loopback address per test index (PORT and PORT+1: publisher and requests), apart per
// test process so parallel CTest runs do not collide; `test` is 0..9. Below Linux's ephemeral
// range (32768-60999), where a retrying SUB socket can connect to itself (tests/net).
inline std::string address(int test) {
  return "tcp://127.0.0.1:" + std::to_string(20000 + int(getpid() % 600) * 20 + 2 * test);
}

// A background ddish, stdout to LOG.out and stderr to LOG; killed by the destructor.
class Process {
 public:
  Process(const std::vector<std::string>& args, const fs::path& log) {
    std::vector<char*> argv;
    std::vector<std::string> all = {DDISH_EXE};
    all.insert(all.end(), args.begin(), args.end());
    for (std::string& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, (log.string() + ".out").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, log.string().c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (posix_spawn(&pid_, DDISH_EXE, &actions, nullptr, argv.data(), environ) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&actions);
  }
  ~Process() { kill(SIGKILL); }
  void kill(int signal) {
    if (pid_ <= 0) return;
    ::kill(pid_, signal);
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
  }
  // Sends `signal` and waits (bounded) for the exit; its exit code, or -1 (then killed).
  int stop(int signal, double seconds) {
    if (pid_ <= 0) return -1;
    ::kill(pid_, signal);
    const int code = wait(seconds);
    kill(SIGKILL);
    return code;
  }
  // Waits (bounded) for the process to exit by itself; its exit code, or -1.
  int wait(double seconds) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end) {
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return -1;
  }

 private:
  pid_t pid_ = -1;
};

// Waits (bounded) until the file contains `text`.
inline bool wait_for(const fs::path& file, const std::string& text, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (slurp(file).find(text) != std::string::npos) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

// Occurrences of `text` in a file.
inline std::size_t count_in(const fs::path& file, const std::string& text) {
  const std::string s = slurp(file);
  std::size_t n = 0;
  for (std::size_t at = 0; (at = s.find(text, at)) != std::string::npos; at += text.size()) ++n;
  return n;
}

}  // namespace cli
