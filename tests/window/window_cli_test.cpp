// `ddish render --window` end to end under a private Xvfb whose screen is exactly the frame's
// size: the window opens fullscreen on lavapipe, presents 10 frames, holds the last one, and a
// screenshot of the screen (xwd) equals the PNG the same run wrote of that frame. Tolerance 0:
// the window's image is the renderer's display bytes (atlas) or the GPU interleave (lenticular,
// equal bit for bit to the CPU's: test_display's GpuCompositorTest), copied 1:1 (nearest blit)
// into a UNORM swapchain, and Xvfb's 24-bit visual keeps 8 bits a channel. Single view, stereo
// pair and lenticular panel image (a Portrait calibration at its panel's 1536 × 2048, and a
// 16-inch-like one on a small panel with flipImageX, flipImageY and flipSubp). The single view
// keeps the status text on and leaves its box out of the comparison, reading the box back glyph
// by glyph instead; the others run with --no-status. Without a display server --window is one
// line and exit 2.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <set>
#include <string>
#include <thread>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "../app/cli_runner.h"
#include "../display/status_text.h"
#include "xvfb.h"
#include "xwd_image.h"

namespace {

namespace fs = std::filesystem;
using window_test::Rgb8Image;
using window_test::Xvfb;

Rgb8Image read_png(const fs::path& p) {
  auto in = OIIO::ImageInput::open(p.string());
  if (!in) throw std::runtime_error("cannot open " + p.string());
  const OIIO::ImageSpec& spec = in->spec();
  Rgb8Image img;
  img.width = spec.width;
  img.height = spec.height;
  std::vector<std::uint8_t> all(std::size_t(spec.width) * std::size_t(spec.height) * std::size_t(spec.nchannels));
  in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, all.data());
  img.rgb.resize(3 * std::size_t(spec.width) * std::size_t(spec.height));
  for (std::size_t i = 0; i < std::size_t(spec.width) * std::size_t(spec.height); ++i)
    for (std::size_t c = 0; c < 3; ++c) img.rgb[3 * i + c] = all[i * std::size_t(spec.nchannels) + c];
  return img;
}

class WindowCli : public cli::TempDirTest {
 protected:
  WindowCli() : cli::TempDirTest("ddish_window_") {}

  // Starts ddish with `args` on `display`, waits (at most 180 s) until it holds its last frame,
  // takes the screenshot, ends ddish with SIGTERM and returns its exit code (-1: did not hold).
  int run_and_shoot(const std::string& display, const std::string& args, const fs::path& shot,
                    const std::string& env = "") {
    // Appended piece by piece: GCC 12 at -O3 warns (-Wrestrict, a false positive) on long chains.
    std::string cmd = "exec env DISPLAY=";
    cmd += display;
    cmd += ' ';
    cmd += env;
    cmd += ' ';
    cmd += cli::quote(DDISH_EXE);
    cmd += ' ';
    cmd += args;
    cmd += " >";
    cmd += cli::quote((dir_ / "stdout").string());
    cmd += " 2>";
    cmd += cli::quote((dir_ / "stderr").string());
    const pid_t pid = ::fork();
    if (pid == 0) {
      ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    bool held = false;
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(180);
    int status = 0;
    bool exited = false;
    while (std::chrono::steady_clock::now() < until) {
      if (cli::slurp(dir_ / "stderr").find("holding frame") != std::string::npos) {
        held = true;
        break;
      }
      if (::waitpid(pid, &status, WNOHANG) == pid) {
        exited = true;
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    if (held) {
      std::this_thread::sleep_for(std::chrono::milliseconds(300));  // a few held presents
      std::string xwd = "xwd -root -silent -display ";
      xwd += display;
      xwd += " -out ";
      xwd += cli::quote(shot.string());
      EXPECT_EQ(std::system(xwd.c_str()), 0) << xwd;
    }
    if (!exited) {
      ::kill(pid, SIGTERM);
      ::waitpid(pid, &status, 0);
    }
    err_ = cli::slurp(dir_ / "stderr");
    if (!held) return -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

  // Differing channel bytes between the screenshot and the PNG, and the largest difference;
  // pixels inside `skip_w` × `skip_h` at the top-left (the status text's box) are not compared.
  void expect_equal(const fs::path& shot, const fs::path& png, int skip_w = 0, int skip_h = 0) {
    const Rgb8Image a = window_test::read_xwd(shot.string());
    const Rgb8Image b = read_png(png);
    ASSERT_EQ(a.width, b.width);
    ASSERT_EQ(a.height, b.height);
    int differing = 0, largest = 0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) {
      const int x = int(i / 3) % a.width, y = int(i / 3) / a.width;
      if (x < skip_w && y < skip_h) continue;
      const int d = std::abs(int(a.rgb[i]) - int(b.rgb[i]));
      differing += d != 0;
      largest = std::max(largest, d);
    }
    EXPECT_EQ(differing, 0) << "largest difference " << largest << " of " << a.rgb.size() << " bytes";
    // And the frame is a picture, not a blank window equal to a blank file.
    std::set<std::uint32_t> colours;
    for (std::size_t i = 0; i + 2 < b.rgb.size(); i += 3)
      colours.insert(std::uint32_t(b.rgb[i]) | std::uint32_t(b.rgb[i + 1]) << 8 | std::uint32_t(b.rgb[i + 2]) << 16);
    EXPECT_GT(colours.size(), 100u);
  }

  std::string err_;
};

const std::string kFast = " --probe-samples 16 --msaa 1 --frames 10 --window --fullscreen --hold";
const std::string kNoStatus = " --no-status";  // the screenshot is the frame alone

TEST_F(WindowCli, SingleViewScreenshotEqualsTheFileAndShowsTheStatusText) {
  // The status text is on (the default): outside its box the screenshot equals the file; inside,
  // every cell reads back as a glyph of the font (tests/display/status_text.h), and the lines
  // say what the last frame's did: its stage times, 1 view, the probe age, indirect on and the
  // default schedule. The other screenshot tests run with --no-status.
  Xvfb x(384, 64);
  ASSERT_TRUE(x.running()) << "Xvfb did not start";
  const int code = run_and_shoot(x.display(),
                                 "render " + cli::cornell() + " --width 384 --height 64 --out " +
                                     path("out") + kFast,
                                 dir_ / "shot.xwd");
  ASSERT_EQ(code, 0) << err_;
  EXPECT_NE(err_.find("frame 10/10"), std::string::npos) << err_;
  const int box_w = ddish::display::status_box_width(1), box_h = ddish::display::status_box_height(2, 1);
  expect_equal(dir_ / "shot.xwd", dir_ / "out" / "frame_0009.png", box_w, box_h);
  const Rgb8Image shot = window_test::read_xwd((dir_ / "shot.xwd").string());
  const std::vector<std::string> lines = ddish::display::test::read_status(
      [&](int px, int py) {
        const std::size_t i = 3 * (std::size_t(py) * std::size_t(shot.width) + std::size_t(px));
        return std::uint32_t(shot.rgb[i]) | std::uint32_t(shot.rgb[i + 1]) << 8 | std::uint32_t(shot.rgb[i + 2]) << 16;
      },
      2, 1);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_TRUE(std::regex_match(lines[0], std::regex(R"(PROBES \d+\.\d  RASTER \d+\.\d  PRESENT \d+\.\d MS)")))
      << lines[0];
  EXPECT_TRUE(std::regex_match(lines[1], std::regex(R"(1 VIEW  PROBE AGE \d+  INDIRECT ON  VISIBILITY)")))
      << lines[1];
}

TEST_F(WindowCli, StereoScreenshotEqualsTheSideBySideFile) {
  Xvfb x(128, 48);
  ASSERT_TRUE(x.running()) << "Xvfb did not start";
  const int code = run_and_shoot(x.display(),
                                 "render " + cli::cornell() +
                                     " --display stereo --width 64 --height 48 --out " +
                                     path("out") + kFast + kNoStatus,
                                 dir_ / "shot.xwd");
  ASSERT_EQ(code, 0) << err_;
  fs::path png;
  for (const auto& e : fs::directory_iterator(dir_ / "out"))
    if (e.path().extension() == ".png") png = e.path();
  ASSERT_FALSE(png.empty());
  expect_equal(dir_ / "shot.xwd", png);
}

TEST_F(WindowCli, LenticularScreenshotEqualsTheCpuPanelFileWithoutValidationErrors) {
  // A Portrait calibration at the panel's own 1536 × 2048 (the magnitudes of a unit's
  // visual.json), its 48 views small (21 × 28) so that the frames stay cheap: the whole panel
  // image, GPU interleave against the CPU's.
  const fs::path cal = dir_ / "visual.json";
  std::ofstream(cal) << R"({"pitch": {"value": 52.58737671470091}, "slope": {"value": -7.196136200157333},
    "center": {"value": 0.4321881363063158}, "DPI": {"value": 324.0}, "screenW": {"value": 1536.0},
    "screenH": {"value": 2048.0}, "invView": {"value": 1.0}, "flipImageX": {"value": 0.0},
    "flipImageY": {"value": 0.0}, "flipSubp": {"value": 0.0}})";
  Xvfb x(1536, 2048);
  ASSERT_TRUE(x.running()) << "Xvfb did not start";
  const int code = run_and_shoot(x.display(),
                                 "render " + cli::cornell() +
                                     " --display looking-glass-portrait --width 21 --height 28"
                                     " --calibration " + cli::quote(cal.string()) + " --out " +
                                     path("out") + kFast + kNoStatus,
                                 dir_ / "shot.xwd", "DDISH_VALIDATION=1");
  ASSERT_EQ(code, 0) << err_;
  EXPECT_NE(err_.find("lenticular panel image 1536x2048"), std::string::npos) << err_;
  EXPECT_NE(err_.find("validation: 0 errors"), std::string::npos) << err_;
  expect_equal(dir_ / "shot.xwd", dir_ / "out" / "cornell_box_lenticular.png");
}

TEST_F(WindowCli, SixteenInchLenticularWithFlipsScreenshotEqualsTheCpuPanelFile) {
  // The 16-inch's 45 views and its lenticules across a 160 × 90 panel (its DPI shrunk with the
  // screen: 3840 / 283 inches wide), mounted mirrored with BGR subpixels.
  const fs::path cal = dir_ / "visual.json";
  std::ofstream(cal) << R"({"pitch": {"value": 47.58}, "slope": {"value": -5.49},
    "center": {"value": 0.09}, "DPI": {"value": 11.7917}, "screenW": {"value": 160.0},
    "screenH": {"value": 90.0}, "invView": {"value": 0.0}, "flipImageX": {"value": 1.0},
    "flipImageY": {"value": 1.0}, "flipSubp": {"value": 1.0}})";
  Xvfb x(160, 90);
  ASSERT_TRUE(x.running()) << "Xvfb did not start";
  const int code = run_and_shoot(x.display(),
                                 "render " + cli::cornell() +
                                     " --display looking-glass-16 --width 41 --height 23"
                                     " --calibration " + cli::quote(cal.string()) + " --out " +
                                     path("out") + kFast + kNoStatus,
                                 dir_ / "shot.xwd");
  ASSERT_EQ(code, 0) << err_;
  EXPECT_NE(err_.find("lenticular panel image 160x90"), std::string::npos) << err_;
  expect_equal(dir_ / "shot.xwd", dir_ / "out" / "cornell_box_lenticular.png");
}

TEST_F(WindowCli, NoDisplayServerIsOneLineAndExit2) {
  const cli::Result r = cli::run_ddish(dir_, "render " + cli::cornell() + " --window --frames 1 --out " +
                                                 path("out"),
                                       "env -u DISPLAY -u WAYLAND_DISPLAY");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("ddish: error: --window needs a display server"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST_F(WindowCli, WindowOptionsWithoutWindowAreRefused) {
  const cli::Result r = cli::run_ddish(dir_, "render " + cli::cornell() + " --fullscreen");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("go with --window"), std::string::npos) << r.err;
}

}  // namespace
