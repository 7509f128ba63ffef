// The live window's keys and minimise end to end: ddish runs `render --window` (no --frames: it
// runs until the window closes) under a private Xvfb, and the test drives it from outside as a
// user would, with xdotool (Debian `xdotool`): real X key events (XTEST) into the focused
// window, and unmapping and mapping the window, which is what a window manager does to iconify
// and restore it (Xvfb has none; SDL reports an unmap as minimised, a map as restored). Each
// switch is then checked in the run's --timings, frame by frame, from the frame where the run's
// log says it took effect: I stops the probe updates and I again restarts them; U changes the
// scheduler's mode and back; while minimised no frame is drawn or presented, and the run goes on
// once restored. Esc ends each run, which must exit 0. Frames are tiny (64 × 48, 16 samples a
// probe, no MSAA), and every wait is bounded.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../app/cli_runner.h"
#include "xvfb.h"

namespace {

namespace fs = std::filesystem;
using window_test::Xvfb;
using Clock = std::chrono::steady_clock;

// One `ddish render --window` run in the background, its stderr in a file of the test's folder.
class LiveRun {
 public:
  LiveRun(const fs::path& dir, const std::string& display, const std::string& args)
      : dir_(dir), display_(display) {
    std::string cmd = "exec env DISPLAY=";
    cmd += display;
    cmd += ' ';
    cmd += cli::quote(DDISH_EXE);
    cmd += ' ';
    cmd += args;
    cmd += " >";
    cmd += cli::quote((dir / "stdout").string());
    cmd += " 2>";
    cmd += cli::quote((dir / "stderr").string());
    pid_ = ::fork();
    if (pid_ == 0) {
      ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
  }
  ~LiveRun() {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }

  std::string err() const { return cli::slurp(dir_ / "stderr"); }
  // Progress lines ("frame K/...") in a log, in the log so far, and before its first `marker`.
  static int frames_in(const std::string& log) {
    int n = 0;
    for (std::size_t at = 0; (at = log.find("\nframe ", at)) != std::string::npos; ++at) ++n;
    return n + (log.rfind("frame ", 0) == 0);
  }
  int frames() const { return frames_in(err()); }
  int frames_before(const std::string& marker) const {
    const std::string log = err();
    const std::size_t at = log.find(marker);
    return at == std::string::npos ? -1 : frames_in(log.substr(0, at));
  }

  // Waits at most `seconds` for `done`; false when it did not come or ddish exited first.
  bool wait_for(const std::function<bool()>& done, double seconds) {
    const auto until = Clock::now() + std::chrono::duration<double>(seconds);
    while (Clock::now() < until) {
      if (done()) return true;
      if (exited()) return done();
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    return false;
  }
  bool wait_frames(int n, double seconds) {
    return wait_for([&] { return frames() >= n; }, seconds);
  }
  bool wait_line(const std::string& text, double seconds) {
    return wait_for([&] { return err().find(text) != std::string::npos; }, seconds);
  }

  // xdotool on the run's display, bounded; its output (a window id) returned.
  std::string xdotool(const std::string& args) const {
    std::string cmd = "DISPLAY=";
    cmd += display_;
    cmd += " timeout 10 xdotool ";
    cmd += args;
    cmd += " 2>>";
    cmd += cli::quote((dir_ / "xdotool.log").string());
    std::string out;
    if (FILE* p = ::popen(cmd.c_str(), "r")) {
      char buf[256];
      while (std::fgets(buf, sizeof buf, p)) out += buf;
      ::pclose(p);
    }
    while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
    return out;
  }
  // The ddish window's id (its title starts with "ddish"), focused for the keys that follow.
  std::string focus_window() {
    window_ = xdotool("search --sync --onlyvisible --name '^ddish'");
    const auto nl = window_.find('\n');
    if (nl != std::string::npos) window_.resize(nl);
    if (!window_.empty()) xdotool("windowfocus --sync " + window_);
    return window_;
  }
  void key(const std::string& name) const { xdotool("key --clearmodifiers " + name); }
  const std::string& window() const { return window_; }

  // Esc, then the exit code (-1: not exited within `seconds`, then killed).
  int quit(double seconds) {
    key("Escape");
    if (!wait_for([&] { return exited(); }, seconds)) return -1;
    pid_ = -1;
    return WIFEXITED(status_) ? WEXITSTATUS(status_) : -1;
  }

 private:
  bool exited() {
    if (pid_ <= 0) return true;
    if (::waitpid(pid_, &status_, WNOHANG) != pid_) return false;
    return true;
  }

  fs::path dir_;
  std::string display_;
  pid_t pid_ = -1;
  int status_ = 0;
  std::string window_;
};

class WindowKeys : public cli::TempDirTest {
 protected:
  WindowKeys() : cli::TempDirTest("ddish_keys_") {}

  std::string args() const {
    return "render " + cli::cornell() +
           " --width 64 --height 48 --probe-samples 16 --msaa 1 --warmup-ms 0 --window --timings " +
           path("timings.json") + " --out " + path("out");
  }
  nlohmann::json frames() const {
    return nlohmann::json::parse(cli::slurp(dir_ / "timings.json"))["frames"];
  }
};

TEST_F(WindowKeys, IPausesProbeUpdatesAndIAgainResumesThem) {
  Xvfb x(160, 120);
  ASSERT_TRUE(x.running()) << "Xvfb did not start";
  LiveRun run(dir_, x.display(), args());
  ASSERT_TRUE(run.wait_frames(2, 120)) << run.err();
  ASSERT_FALSE(run.focus_window().empty()) << cli::slurp(dir_ / "xdotool.log");
  run.key("i");
  ASSERT_TRUE(run.wait_line("I: indirect light off", 30)) << run.err();
  const int off = run.frames_before("I: indirect light off");
  ASSERT_TRUE(run.wait_frames(off + 3, 60)) << run.err();
  run.key("i");
  ASSERT_TRUE(run.wait_line("I: indirect light on", 30)) << run.err();
  const int on = run.frames_before("I: indirect light on");
  ASSERT_TRUE(run.wait_frames(on + 2, 60)) << run.err();
  ASSERT_EQ(run.quit(30), 0) << run.err();
  EXPECT_NE(run.err().find("window closed after frame"), std::string::npos) << run.err();

  const nlohmann::json f = frames();
  ASSERT_GE(int(f.size()), on + 2);
  ASSERT_GE(on - off, 3);
  for (int k = 0; k < int(f.size()); ++k) {
    const auto updates = f[std::size_t(k)]["probe_updates"].get<std::uint64_t>();
    SCOPED_TRACE("frame " + std::to_string(k) + ", off from " + std::to_string(off) + " to " +
                 std::to_string(on));
    if (k >= off && k < on)
      EXPECT_EQ(updates, 0u);
    else
      EXPECT_GT(updates, 0u);
  }
}

TEST_F(WindowKeys, USwitchesTheScheduleAndBack) {
  Xvfb x(160, 120);
  ASSERT_TRUE(x.running()) << "Xvfb did not start";
  LiveRun run(dir_, x.display(), args());
  ASSERT_TRUE(run.wait_frames(2, 120)) << run.err();
  ASSERT_FALSE(run.focus_window().empty()) << cli::slurp(dir_ / "xdotool.log");
  run.key("u");
  ASSERT_TRUE(run.wait_line("U: schedule uniform", 30)) << run.err();
  const int uniform = run.frames_before("U: schedule uniform");
  ASSERT_TRUE(run.wait_frames(uniform + 2, 60)) << run.err();
  run.key("u");
  ASSERT_TRUE(run.wait_line("U: schedule visibility", 30)) << run.err();
  const int back = run.frames_before("U: schedule visibility");
  ASSERT_TRUE(run.wait_frames(back + 2, 60)) << run.err();
  ASSERT_EQ(run.quit(30), 0) << run.err();

  const nlohmann::json f = frames();
  ASSERT_GE(int(f.size()), back + 2);
  for (int k = 0; k < int(f.size()); ++k)
    EXPECT_EQ(f[std::size_t(k)]["scheduler"]["mode"],
              k >= uniform && k < back ? "uniform" : "visibility")
        << "frame " << k << ", uniform from " << uniform << " to " << back;
}

TEST_F(WindowKeys, MinimisedDrawsNothingAndRestoredGoesOn) {
  Xvfb x(160, 120);
  ASSERT_TRUE(x.running()) << "Xvfb did not start";
  LiveRun run(dir_, x.display(), args());
  ASSERT_TRUE(run.wait_frames(2, 120)) << run.err();
  ASSERT_FALSE(run.focus_window().empty()) << cli::slurp(dir_ / "xdotool.log");
  run.xdotool("windowunmap --sync " + run.window());
  ASSERT_TRUE(run.wait_line("window minimised", 30)) << run.err();
  const int before = run.frames();
  EXPECT_EQ(before, run.frames_before("window minimised"));
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  EXPECT_EQ(run.frames(), before) << "frames were drawn while minimised";
  run.xdotool("windowmap --sync " + run.window());
  ASSERT_TRUE(run.wait_line("window restored after", 30)) << run.err();
  ASSERT_TRUE(run.wait_frames(before + 2, 60)) << run.err();
  run.focus_window();
  ASSERT_EQ(run.quit(30), 0) << run.err();

  const std::string log = run.err();
  const std::size_t at = log.find("window restored after ");
  const double paused_ms = std::stod(log.substr(at + std::string("window restored after ").size()));
  EXPECT_GE(paused_ms, 1000.0);  // at least the second the test kept it unmapped
  EXPECT_GE(int(frames().size()), before + 2);
  EXPECT_EQ(int(frames().size()), run.frames());
}

}  // namespace
