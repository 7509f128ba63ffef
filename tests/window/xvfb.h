// A private X server for one test: Xvfb with a screen of the size the test asks for (24-bit) on
// a display number it picks itself (-displayfd: no race between tests started together),
// started in the constructor and stopped (SIGTERM, then waited for) in the destructor. Start-up
// is bounded: the server must report its display within 10 s.
#pragma once

#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <string>

namespace window_test {

class Xvfb {
 public:
  Xvfb(int width, int height) {
    int fds[2];
    if (::pipe(fds) != 0) return;
    std::string screen = std::to_string(width);
    screen += 'x';
    screen += std::to_string(height);
    screen += "x24";
    const std::string fd = std::to_string(fds[1]);
    pid_ = ::fork();
    if (pid_ == 0) {
      ::close(fds[0]);
      ::execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", screen.c_str(),
               "-nolisten", "tcp", "-noreset", static_cast<char*>(nullptr));
      ::_exit(127);
    }
    ::close(fds[1]);
    // Xvfb writes the display number and a newline once it accepts connections.
    std::string number;
    pollfd p{fds[0], POLLIN, 0};
    while (pid_ > 0 && ::poll(&p, 1, 10000) == 1) {
      char c = 0;
      if (::read(fds[0], &c, 1) != 1) break;
      if (c == '\n') {
        display_ = ":" + number;
        break;
      }
      number += c;
    }
    ::close(fds[0]);
    if (display_.empty()) stop();
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
