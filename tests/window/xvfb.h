// A private X server for one test: Xvfb on a free display number with a screen of the size the
// test asks for (24-bit), started in the constructor and stopped (SIGTERM, then waited for) in the
// destructor. Start-up is bounded: the server's socket must appear within 10 s.
#pragma once

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>

namespace window_test {

class Xvfb {
 public:
  Xvfb(int width, int height) {
    for (int n = 90 + int(::getpid() % 50); n < 200 && pid_ <= 0; ++n) {
      if (std::filesystem::exists("/tmp/.X11-unix/X" + std::to_string(n)) ||
          std::filesystem::exists("/tmp/.X" + std::to_string(n) + "-lock"))
        continue;
      // Appended piece by piece: GCC 12 at -O3 warns (-Wrestrict, a false positive) on
      // "literal" + std::string.
      std::string display = ":";
      display += std::to_string(n);
      std::string screen = std::to_string(width);
      screen += 'x';
      screen += std::to_string(height);
      screen += "x24";
      pid_ = ::fork();
      if (pid_ == 0) {
        ::execlp("Xvfb", "Xvfb", display.c_str(), "-screen", "0", screen.c_str(), "-nolisten",
                 "tcp", "-noreset", static_cast<char*>(nullptr));
        ::_exit(127);
      }
      const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(10);
      while (std::chrono::steady_clock::now() < until) {
        if (std::filesystem::exists("/tmp/.X11-unix/X" + std::to_string(n))) {
          display_ = display;
          return;
        }
        int status = 0;
        if (::waitpid(pid_, &status, WNOHANG) == pid_) break;  // it died (display taken?)
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
      stop();
    }
  }
  ~Xvfb() { stop(); }
  Xvfb(const Xvfb&) = delete;
  Xvfb& operator=(const Xvfb&) = delete;

  bool running() const { return !display_.empty(); }
  const std::string& display() const { return display_; }

 private:
  void stop() {
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      int status = 0;
      ::waitpid(pid_, &status, 0);
    }
    pid_ = -1;
    display_.clear();
  }
  pid_t pid_ = -1;
  std::string display_;
};

}  // namespace window_test
