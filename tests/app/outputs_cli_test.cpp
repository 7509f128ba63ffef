// What ddish leaves on disk when writing goes wrong or the run is stopped (issue 15):
// - an output folder that cannot be written is one error line and exit 2 before the scene is
//   loaded (render, reference, probes, --timings, --convergence);
// - a file size limit (RLIMIT_FSIZE, through prlimit) and a full disk (a small tmpfs, where this
//   test may mount one) are one error line and exit 2, and no partial file is left;
// - SIGINT / SIGTERM end the frame loop after the current frame: exit 128 + signal, the stop is
//   reported with the frame reached, every file left is whole and --timings has every frame
//   done; a stop that lands while a frame renders without being read back still writes that
//   frame; a second SIGINT aborts at once and still leaves no temporary behind.
#include <signal.h>
#include <spawn.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fcntl.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using cli::quote;
using cli::Result;
using cli::slurp;

// Small and quick: one frame is a fraction of a second on lavapipe.
const std::string kTiny = " --grid 2,2,2 --probe-samples 4 --bounces 1 --msaa 1 --width 32 --height 32";

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

void expect_one_error_line(const Result& r, const std::string& must_contain) {
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(r.err.rfind("ddish: error: ", 0), 0u) << r.err;
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
  EXPECT_TRUE(contains(r.err, must_contain)) << r.err;
}

// A run that had started (its log on stderr) and then failed: exit 2, and the one error line is
// the last line of stderr.
void expect_error_as_last_line(const Result& r, const std::string& must_contain) {
  EXPECT_EQ(r.code, 2) << r.err;
  ASSERT_FALSE(r.err.empty());
  ASSERT_EQ(r.err.back(), '\n');
  const std::size_t start = r.err.rfind('\n', r.err.size() - 2) + 1;  // npos + 1 == 0
  const std::string last = r.err.substr(start);
  EXPECT_EQ(last.rfind("ddish: error: ", 0), 0u) << r.err;
  EXPECT_EQ(r.err.find("ddish: error: "), start) << "more than one error line: " << r.err;
  EXPECT_TRUE(contains(last, must_contain)) << r.err;
}

// Names of the files in `dir` (not recursive).
std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// No temporary of io/atomic_file.h (".NAME.ddish-PID-N.part") and no write check file is left.
void expect_no_temporaries(const fs::path& dir) {
  for (const std::string& n : names_in(dir)) {
    EXPECT_FALSE(n.size() > 5 && n.compare(n.size() - 5, 5, ".part") == 0) << n;
    EXPECT_FALSE(contains(n, ".ddish-write-check")) << n;
  }
}

// A whole PNG: the signature, then chunks that end exactly at the end of the file with IEND.
bool whole_png(const fs::path& p) {
  const std::string b = slurp(p);
  if (b.size() < 8 || b.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0) return false;
  std::size_t at = 8;
  while (at + 12 <= b.size()) {
    std::uint32_t len = 0;
    for (std::size_t i = 0; i < 4; ++i) len = (len << 8) | static_cast<unsigned char>(b[at + i]);
    const std::string type = b.substr(at + 4, 4);
    at += 12 + std::size_t(len);
    if (type == "IEND") return at == b.size();
  }
  return false;
}

// A whole EXR as far as the name shows: the magic number, and `ddish compare` reads it back
// against itself (a truncated EXR fails to read).
bool exr_magic(const fs::path& p) {
  const std::string b = slurp(p);
  return b.size() > 4 && b.compare(0, 4, "\x76\x2f\x31\x01") == 0;
}

class OutputsCli : public cli::TempDirTest {
 protected:
  OutputsCli() : TempDirTest("ddish_outputs_cli_") {}

  // A regular file, so that DIR/file/sub can never be created.
  std::string blocked(const std::string& below) const {
    std::ofstream(dir_ / "a_file") << "x";
    return quote((dir_ / "a_file" / below).string());
  }

  // ddish started in the background, its stderr in dir_/stderr (child_err()).
  pid_t spawn(const std::vector<std::string>& args) {
    std::vector<std::string> argv{DDISH_EXE};
    argv.insert(argv.end(), args.begin(), args.end());
    std::vector<char*> cargv;
    for (std::string& a : argv) cargv.push_back(a.data());
    cargv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    const std::string err = (dir_ / "stderr").string();
    const std::string out = (dir_ / "stdout").string();
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid = -1;
    const int rc = posix_spawn(&pid, DDISH_EXE, &actions, nullptr, cargv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    EXPECT_EQ(rc, 0);
    return pid;
  }
  std::string child_err() const { return slurp(dir_ / "stderr"); }

  // Waits (at most `seconds`) until the child's stderr contains `text`.
  bool wait_for_text(const std::string& text, double seconds) const {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end) {
      if (contains(child_err(), text)) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  }

  // Waits (at most `seconds`) until `path` exists.
  static bool wait_for_file(const fs::path& path, double seconds) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (std::chrono::steady_clock::now() < end) {
      if (fs::exists(path)) return true;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return false;
  }

  // The child's exit code (128 + signal if a signal killed it), or -1 after `seconds` (the
  // child is then killed, so that a hang fails the test instead of stalling it).
  static int wait_exit(pid_t pid, double seconds) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    int status = 0;
    while (std::chrono::steady_clock::now() < end) {
      const pid_t r = waitpid(pid, &status, WNOHANG);
      if (r == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
    return -1;
  }

  // An endless render (100000 frames) of the Cornell box; `size` pixels square, `samples` paths
  // per probe of a grid^3 volume.
  std::vector<std::string> render_args(const std::string& out, bool every, int size = 32,
                                       int samples = 4, int grid = 2) const {
    const std::string g = std::to_string(grid);
    std::vector<std::string> args{"render", std::string(DDISH_SOURCE_DIR) + "/scenes/cornell_box.gltf",
                                  "--grid", g + "," + g + "," + g, "--probe-samples",
                                  std::to_string(samples), "--bounces", "1", "--msaa", "1",
                                  "--width", std::to_string(size), "--height", std::to_string(size),
                                  "--frames", "100000", "--out", out,
                                  "--timings", (dir_ / "timings.json").string()};
    if (every) args.push_back("--every");
    return args;
  }
};

TEST_F(OutputsCli, UnwritableOutputFolderFailsBeforeTheScene) {
  // A missing scene would be reported after the folder: the folder check comes first.
  const std::string scene = cli::cornell();
  expect_one_error_line(run("render " + scene + " --out " + blocked("out")),
                        "cannot write to output folder");
  expect_one_error_line(run("render " + scene + " --out " + path("out") + " --timings " +
                            blocked("t.json")),
                        "cannot write to output folder");
  expect_one_error_line(run("reference " + scene + " --spp 1 --out " + blocked("ref")),
                        "cannot write to output folder");
  expect_one_error_line(run("reference " + scene + " --spp 1 --out " + path("ref") +
                            " --convergence " + blocked("c.csv")),
                        "cannot write to output folder");
  expect_one_error_line(run("probes " + scene + " --out " + blocked("v.ddpv")),
                        "cannot write to output folder");
  expect_one_error_line(run("probes " + scene + " --out " + path("")), "it is a folder");
  // The reason is the system's: the parent is not a folder.
  EXPECT_TRUE(contains(run("render " + scene + " --out " + blocked("out")).err, "Not a directory"));
  EXPECT_FALSE(fs::exists(dir_ / "ref" / "reference.exr"));
}

// ddish reference and ddish probes: render cannot run under a file size limit on lavapipe, whose
// device memory lives in memfd files that the limit also caps (see FileSizeLimitStopsRender).
TEST_F(OutputsCli, FileSizeLimitIsOneErrorLineAndLeavesNoPartialFile) {
  // 8000 bytes: the write check fits, the 64x64 float EXR (48 KiB raw) does not.
  const Result r = run("reference " + cli::cornell() + " --spp 1 --bounces 1 --width 64 "
                       "--height 64 --out " + path("out"),
                       "prlimit --fsize=8000");
  expect_error_as_last_line(r, "cannot write " + (dir_ / "out" / "reference.exr").string() +
                                   ": File too large");
  expect_no_temporaries(dir_ / "out");
  EXPECT_FALSE(fs::exists(dir_ / "out" / "reference.exr"));
  // A probe volume (512 probes of 56 bytes) and its summary the same way.
  const Result p = run("probes " + cli::cornell() + " --grid 8,8,8 --probe-samples 1 --out " +
                           path("vol/v.ddpv"),
                       "prlimit --fsize=8000");
  EXPECT_EQ(p.code, 2);
  EXPECT_EQ(p.err, "ddish: error: cannot write " + (dir_ / "vol" / "v.ddpv").string() +
                       ": File too large\n");
  EXPECT_TRUE(names_in(dir_ / "vol").empty());
}

TEST_F(OutputsCli, FileSizeLimitStopsRenderBeforeTheDriverCrashes) {
  const Result r = run("render " + cli::cornell() + kTiny + " --out " + path("out"),
                       "prlimit --fsize=8000");
  // lavapipe: refused up front (it would die of SIGBUS); a GPU: the EXR does not fit.
  expect_error_as_last_line(r, "");
  EXPECT_TRUE(contains(r.err, "a file size limit of 8000 bytes is set (ulimit -f)") ||
              contains(r.err, "File too large"))
      << r.err;
  expect_no_temporaries(dir_ / "out");
}

// A real ENOSPC needs a filesystem that fills up: a tmpfs mounted here, where that is allowed
// (root in a container that may mount); elsewhere the file size limit above stands in for it.
class FullDisk : public OutputsCli {
 protected:
  void SetUp() override {
    OutputsCli::SetUp();
    disk_ = dir_ / "disk";
    fs::create_directories(disk_);
    if (::mount("tmpfs", disk_.c_str(), "tmpfs", 0, "size=64k") != 0)
      GTEST_SKIP() << "cannot mount a tmpfs here (" << std::strerror(errno) << ")";
    mounted_ = true;
  }
  void TearDown() override {
    if (mounted_) ::umount(disk_.c_str());
    OutputsCli::TearDown();
  }
  fs::path disk_;
  bool mounted_ = false;
};

TEST_F(FullDisk, DiskFullDuringTheRunIsOneErrorLine) {
  // 64 KiB: a 256x256 frame's EXR (768 KiB raw) cannot fit.
  const Result r = run("render " + cli::cornell() +
                       " --grid 2,2,2 --probe-samples 4 --bounces 1 --msaa 1 --width 256 "
                       "--height 256 --out " + quote((disk_ / "out").string()));
  expect_error_as_last_line(r, "No space left on device");
  expect_no_temporaries(disk_ / "out");
  for (const std::string& n : names_in(disk_ / "out"))
    if (n.ends_with(".png")) {
      EXPECT_TRUE(whole_png(disk_ / "out" / n)) << n;
    }
}

TEST_F(FullDisk, FullDiskBeforeTheRunFailsBeforeTheScene) {
  {
    std::ofstream fill(disk_ / "fill", std::ios::binary);
    const std::string block(4096, 'x');
    while (fill.write(block.data(), std::streamsize(block.size()))) {
    }
  }
  const Result r = run("render " + cli::cornell() + kTiny + " --out " + quote((disk_ / "out").string()));
  expect_one_error_line(r, "cannot write to output folder");
  EXPECT_TRUE(contains(r.err, "No space left on device")) << r.err;
  EXPECT_FALSE(contains(r.err, "render:")) << "the run started: " << r.err;
}

TEST_F(OutputsCli, SigintEndsAfterTheCurrentFrameWithWholeFiles) {
  const fs::path out = dir_ / "out";
  const pid_t pid = spawn(render_args(out.string(), false));
  ASSERT_TRUE(wait_for_text("frame 3/100000", 120)) << child_err();
  ASSERT_EQ(kill(pid, SIGINT), 0);
  const int code = wait_exit(pid, 60);
  const std::string err = child_err();
  EXPECT_EQ(code, 130) << err;
  EXPECT_TRUE(contains(err, "ddish: SIGINT: stopping after the current frame")) << err;
  const std::size_t at = err.find("render: stopped by SIGINT after frame ");
  ASSERT_NE(at, std::string::npos) << err;
  const int done = std::stoi(err.substr(at + 38));
  EXPECT_GE(done, 3);
  EXPECT_TRUE(contains(err, "of 100000")) << err;
  // The last finished frame is written (whole), and only it.
  char frame[32];
  std::snprintf(frame, sizeof frame, "frame_%04d", done - 1);
  EXPECT_EQ(names_in(out), (std::vector<std::string>{std::string(frame) + ".exr",
                                                     std::string(frame) + ".png"}));
  EXPECT_TRUE(whole_png(out / (std::string(frame) + ".png")));
  EXPECT_TRUE(exr_magic(out / (std::string(frame) + ".exr")));
  EXPECT_TRUE(contains(slurp(dir_ / "stdout"), "wrote " + (out / frame).string() + ".png"))
      << slurp(dir_ / "stdout");
  const std::string exr = quote((out / (std::string(frame) + ".exr")).string());
  const Result self = run("compare " + exr + " " + exr);
  EXPECT_EQ(self.code, 0) << self.err;
  EXPECT_TRUE(contains(self.out, "inf")) << self.out;
  // --timings has every frame done; only the last came back to the CPU.
  const nlohmann::json timings = nlohmann::json::parse(slurp(dir_ / "timings.json"));
  ASSERT_EQ(timings["frames"].size(), std::size_t(done));
  for (int k = 0; k < done; ++k)
    EXPECT_EQ(timings["frames"][std::size_t(k)]["read_back"].get<bool>(), k + 1 == done) << k;
}

// Only written frames are read back (FrameLoopOptions::read_back), so a stop usually lands while
// a frame renders that will not be read back; that frame is rendered again, read back and
// written as the last, with the pixels of a run that ends there. Without indirect light nearly
// all of a frame is its rasterization, so almost every stop lands in it: the test tries up to
// four runs until one did (each run checks the frame written either way).
TEST_F(OutputsCli, StopDuringAFrameNotReadBackStillWritesIt) {
  const auto args = [&](const fs::path& out, int frames) {
    return std::vector<std::string>{
        "render", std::string(DDISH_SOURCE_DIR) + "/scenes/cornell_animated.gltf", "--no-indirect",
        "--msaa", "4", "--width", "128", "--height", "128", "--fps", "4", "--warmup-ms", "0",
        "--frames", std::to_string(frames), "--out", out.string(), "--timings",
        (dir_ / "timings.json").string()};
  };
  bool again = false;
  for (int attempt = 0; attempt < 4 && !again; ++attempt) {
    const fs::path out = dir_ / ("stopped" + std::to_string(attempt));
    const pid_t pid = spawn(args(out, 100000));
    ASSERT_TRUE(wait_for_text("frame 2/100000", 120)) << child_err();
    ASSERT_EQ(kill(pid, SIGINT), 0);
    ASSERT_EQ(wait_exit(pid, 60), 130) << child_err();
    const std::string err = child_err();
    const std::size_t at = err.find("render: stopped by SIGINT after frame ");
    ASSERT_NE(at, std::string::npos) << err;
    const int done = std::stoi(err.substr(at + 38));
    const nlohmann::json timings = nlohmann::json::parse(slurp(dir_ / "timings.json"));
    ASSERT_EQ(timings["frames"].size(), std::size_t(done));
    for (int k = 0; k + 1 < done; ++k) {
      const nlohmann::json& f = timings["frames"][std::size_t(k)];
      EXPECT_FALSE(f["read_back"].get<bool>()) << "frame " << k << " is not written";
      EXPECT_EQ(f["stages_ms"]["readback"].get<double>(), 0.0) << k;
      EXPECT_FALSE(f["rendered_again"].get<bool>()) << k;
    }
    const nlohmann::json& last = timings["frames"].back();
    EXPECT_TRUE(last["read_back"].get<bool>());
    again = last["rendered_again"].get<bool>();
    // A run that ends at that frame by its --frames draws the same pose: the same bytes.
    char frame[32];
    std::snprintf(frame, sizeof frame, "frame_%04d.png", done - 1);
    const fs::path ended = dir_ / ("ended" + std::to_string(attempt));
    const pid_t whole = spawn(args(ended, done));
    ASSERT_EQ(wait_exit(whole, 120), 0) << child_err();
    EXPECT_EQ(names_in(out), (std::vector<std::string>{std::string(frame, 10) + ".exr", frame}));
    EXPECT_TRUE(slurp(out / frame) == slurp(ended / frame)) << frame << " differs";
    std::printf("attempt %d: stopped after frame %d, %s\n", attempt, done,
                again ? "rendered again" : "the stop came outside the render");
  }
  EXPECT_TRUE(again) << "no stop of four landed in a frame's rendering";
}

TEST_F(OutputsCli, SigtermWithEveryLeavesEveryFrameWhole) {
  const fs::path out = dir_ / "out";
  const pid_t pid = spawn(render_args(out.string(), true));
  ASSERT_TRUE(wait_for_text("frame 4/100000", 120)) << child_err();
  ASSERT_EQ(kill(pid, SIGTERM), 0);
  const int code = wait_exit(pid, 60);
  const std::string err = child_err();
  EXPECT_EQ(code, 143) << err;
  const std::size_t at = err.find("render: stopped by SIGTERM after frame ");
  ASSERT_NE(at, std::string::npos) << err;
  const int done = std::stoi(err.substr(at + 39));
  const std::vector<std::string> names = names_in(out);
  EXPECT_EQ(names.size(), 2u * std::size_t(done));
  for (const std::string& n : names) {
    if (n.ends_with(".png")) {
      EXPECT_TRUE(whole_png(out / n)) << n;
    }
    if (n.ends_with(".exr")) {
      EXPECT_TRUE(exr_magic(out / n)) << n;
    }
  }
  expect_no_temporaries(out);
}

TEST_F(OutputsCli, SecondSigintAbortsAtOnceWithoutTemporaries) {
  const fs::path out = dir_ / "out";
  // 512 probes at 2048 paths: a probe update takes over a second here, so both signals land
  // inside frame 2. Frame 1 goes to the writer thread (app/output_queue.h) as frame 2 starts;
  // the signals wait until its files are there, since an abort drops what is not yet written.
  const pid_t pid = spawn(render_args(out.string(), true, 64, 2048, 8));
  ASSERT_TRUE(wait_for_text("frame 1/100000", 120)) << child_err();
  ASSERT_TRUE(wait_for_file(out / "frame_0000.exr", 60)) << child_err();
  ASSERT_EQ(kill(pid, SIGINT), 0);
  ASSERT_TRUE(wait_for_text("stopping after the current frame", 30)) << child_err();
  const auto sent = std::chrono::steady_clock::now();
  ASSERT_EQ(kill(pid, SIGINT), 0);
  const int code = wait_exit(pid, 30);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  const std::string err = child_err();
  EXPECT_EQ(code, 130) << err;
  EXPECT_TRUE(contains(err, "ddish: SIGINT: aborted")) << err;
  EXPECT_FALSE(contains(err, "render: stopped by SIGINT")) << err;
  EXPECT_FALSE(contains(err, "frame 2/100000")) << "frame 2 was finished: " << err;
  std::printf("second SIGINT to exit: %.3f s\n", seconds);  // for the record, not a pass mark
  expect_no_temporaries(out);
  EXPECT_EQ(names_in(out), (std::vector<std::string>{"frame_0000.exr", "frame_0000.png"}));
  EXPECT_TRUE(whole_png(out / "frame_0000.png"));
}

}  // namespace
