#include "app/interrupt.h"

#include <signal.h>
#include <unistd.h>

#include <cstddef>

#include "io/atomic_file.h"

namespace ddish::app {

namespace {

std::atomic<bool> g_graceful{false};
std::atomic<bool> g_stop{false};
std::atomic<int> g_signal{0};

void say(const char* text) {
  // Only async-signal-safe calls here: write(2), and the length counted by hand. A short write
  // of a message is not worth a retry.
  std::size_t length = 0;
  while (text[length] != '\0') ++length;
  [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, text, length);
}

void on_signal(int signal) {
  if (g_graceful.load() && !g_stop.load()) {
    g_signal.store(signal);
    g_stop.store(true);
    say(signal == SIGINT
            ? "\nddish: SIGINT: stopping after the current frame (Ctrl-C again to abort now)\n"
            : "\nddish: SIGTERM: stopping after the current frame (again to abort now)\n");
    return;
  }
  io::remove_partial_files();
  say(signal == SIGINT ? "\nddish: SIGINT: aborted\n" : "\nddish: SIGTERM: aborted\n");
  ::_exit(interrupted_exit_code(signal));
}

void install(int signal) {
  struct sigaction old{};
  if (::sigaction(signal, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) return;
  struct sigaction sa{};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  ::sigaction(signal, &sa, nullptr);
}

}  // namespace

void install_interrupt_handlers() {
  install(SIGINT);
  install(SIGTERM);
  ::signal(SIGXFSZ, SIG_IGN);
}

void allow_graceful_stop() { g_graceful.store(true); }

const std::atomic<bool>& stop_flag() { return g_stop; }

int stop_signal() { return g_signal.load(); }

}  // namespace ddish::app
