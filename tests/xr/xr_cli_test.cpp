// `ddish xr` under the headless test runtime (tests/xr_runtime), through the system loader: what
// the runtime recorded (session.json, each submitted eye as EXR) and what ddish said.
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "../app/cli_runner.h"
#include "metrics/color.h"
#include "metrics/image.h"
#include "metrics/image_io.h"

namespace {

using nlohmann::json;

// The stereo-hmd profile's per-eye angles (displays/stereo-hmd.json) at a small eye size.
constexpr const char* kFov =
    R"("fov_deg": {"left": {"left": -50, "right": 43, "up": 47, "down": -53},
                   "right": {"left": -43, "right": 50, "up": 47, "down": -53}})";
constexpr const char* kCamera = "0,1,3.4,0,1,0,0,1,0";

int count_lines(const std::string& text, const std::string& prefix) {
  int n = 0;
  std::size_t at = 0;
  while (at < text.size()) {
    const std::size_t end = text.find('\n', at);
    if (text.compare(at, prefix.size(), prefix) == 0) ++n;
    if (end == std::string::npos) break;
    at = end + 1;
  }
  return n;
}

class XrCli : public cli::TempDirTest {
 protected:
  XrCli() : TempDirTest("ddish_xr_") {}

  // The runtime's script and environment for a run; the runtime writes under DIR/xr.
  std::string runtime_env(const std::string& script) const {
    std::ofstream(dir_ / "script.json") << script;
    cli::fs::create_directories(dir_ / "xr");
    return "XR_RUNTIME_JSON=" + cli::quote(DDISH_XR_RUNTIME_JSON) + " DDISH_XR_SCRIPT=" + path("script.json") +
           " DDISH_XR_OUT=" + path("xr");
  }
  json session() const {
    std::ifstream in(dir_ / "xr" / "session.json");
    return json::parse(in);
  }
  static std::vector<json> rendered(const json& s) {
    std::vector<json> out;
    for (const json& f : s["frames"])
      if (!f["submitted"].empty()) out.push_back(f);
    return out;
  }
};

TEST_F(XrCli, NoRuntimeIsOneLineNamingWhereTheLoaderLooksAndExitTwo) {
  cli::fs::create_directories(dir_ / "config");
  // No XR_RUNTIME_JSON and no active_runtime.json where the loader looks (an empty config home).
  const cli::Result none = run("xr " + cli::cornell(), "env -u XR_RUNTIME_JSON XDG_CONFIG_HOME=" + path("config") +
                                                           " XDG_CONFIG_DIRS=" + path("config"));
  EXPECT_EQ(none.code, 2);
  EXPECT_EQ(count_lines(none.err, "ddish: error: "), 1) << none.err;
  EXPECT_NE(none.err.find("XR_RUNTIME_JSON"), std::string::npos) << none.err;
  EXPECT_NE(none.err.find("active_runtime.json"), std::string::npos) << none.err;
  EXPECT_EQ(none.err.find("OpenXR-Loader"), std::string::npos) << "the loader's own log leaked: " << none.err;
  const cli::Result missing = run("xr " + cli::cornell(), "XR_RUNTIME_JSON=" + cli::quote(DDISH_XR_MISSING_JSON));
  EXPECT_EQ(missing.code, 2);
  EXPECT_EQ(count_lines(missing.err, "ddish: error: "), 1) << missing.err;
  EXPECT_NE(missing.err.find(std::string("XR_RUNTIME_JSON=") + DDISH_XR_MISSING_JSON), std::string::npos) << missing.err;
  EXPECT_EQ(count_lines(missing.err, ""), 2) << "one line of environment, one error: " << missing.err;
}

// 30 frames with the OpenXR core validation layer and the Vulkan validation layer on: no message
// from either; every rendered frame submitted exactly the poses and FOVs it located; the session
// ends through the app's request when --frames runs out.
TEST_F(XrCli, ThirtyFramesUnderBothValidationLayersSubmitTheLocatedPoses) {
  const std::string script = std::string(R"({"eye_width": 48, "eye_height": 54, )") + kFov +
                             R"(, "keys": [{"frame": 0, "position": [0, 0, 0]},
                                 {"frame": 30, "position": [0.2, 0.05, -0.1], "orientation": [0, 0.258819, 0, 0.9659258]}]})";
  const cli::Result r = run("xr " + cli::cornell() + " --frames 30 --probe-samples 32 --warmup-ms 200 --warmup-samples 64",
                            runtime_env(script) + " DDISH_VALIDATION=1");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("OpenXR core validation on"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("xr: validation: 0 OpenXR messages, 0 Vulkan errors"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("xr: warm-up: "), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("VUID"), std::string::npos) << r.out;  // the layer's text output, if any
  const json s = session();
  const std::vector<json> frames = rendered(s);
  ASSERT_EQ(frames.size(), 30u);
  for (const json& f : frames) {
    ASSERT_EQ(f["submitted"].size(), 2u);
    EXPECT_EQ(f["submitted"], f["located"]) << "frame " << f["index"];
    EXPECT_EQ(f["images"].size(), 2u);
  }
  // The head moved: the last frame's left eye is not where the first one's was.
  EXPECT_NE(frames.front()["located"][0]["position"], frames.back()["located"][0]["position"]);
  const std::vector<std::string> states = s["states"];
  ASSERT_GE(states.size(), 3u);
  EXPECT_EQ(std::vector<std::string>(states.end() - 3, states.end()),
            (std::vector<std::string>{"STOPPING", "IDLE", "EXITING"}));
}

// The submitted eye images are `ddish render --display PROFILE --per-view` of the same eyes:
// same poses (the headset's LOCAL origin at --camera), FOVs and probes (no budget, no warm-up:
// both trace every active probe once at the same seed). Tolerance: at most 1 sRGB code in any
// channel (the two paths decode the same bytes; measured: identical).
TEST_F(XrCli, EachEyeEqualsRenderDisplayStereoForTheSamePosesAndProbes) {
  const std::string script =
      std::string(R"({"eye_width": 64, "eye_height": 72, "ipd": 0.063, "synchronized_frames": 1, )") + kFov + "}";
  const std::string common = std::string(" --camera ") + kCamera + " --frames 1 --budget-ms 0 --warmup-ms 0 --probe-samples 64";
  const cli::Result x = run("xr " + cli::cornell() + common, runtime_env(script));
  ASSERT_EQ(x.code, 0) << x.err;
  std::ofstream(dir_ / "hmd.json") << R"({"name": "test-hmd", "views": 2, "quilt": {"columns": 2, "rows": 1},
    "tile": {"width": 64, "height": 72}, "refresh_hz": 90,
    "camera": {"model": "stereo", "ipd_mm": 63, "eye_fov_deg": {"left": {"left": -50, "right": 43, "up": 47, "down": -53},
               "right": {"left": -43, "right": 50, "up": 47, "down": -53}}}})";
  const cli::Result r = run("render " + cli::cornell() + " --display " + path("hmd.json") + common + " --per-view --out " +
                            path("render"));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::vector<json> frames = rendered(session());
  ASSERT_EQ(frames.size(), 1u);
  for (int e = 0; e < 2; ++e) {
    const auto xr_image = ddish::metrics::read_image(dir_ / "xr" / frames[0]["images"][e].get<std::string>());
    const auto png = ddish::metrics::read_image(dir_ / "render" / ("view_" + std::to_string(e) + ".png"));
    ASSERT_EQ(xr_image.width(), 64);
    ASSERT_EQ(png.width(), xr_image.width());
    ASSERT_EQ(png.height(), xr_image.height());
    int worst = 0;
    double sum = 0.0;
    for (int y = 0; y < png.height(); ++y)
      for (int x0 = 0; x0 < png.width(); ++x0)
        for (int c = 0; c < 3; ++c) {
          const int a = ddish::metrics::srgb8_encode(xr_image.at(x0, y)[c]);
          const int b = ddish::metrics::srgb8_encode(png.at(x0, y)[c]);
          worst = std::max(worst, std::abs(a - b));
          sum += ddish::metrics::srgb8_encode(png.at(x0, y)[c]);
        }
    EXPECT_LE(worst, 1) << "eye " << e;
    EXPECT_GT(sum / (64.0 * 72.0 * 3.0), 10.0) << "eye " << e << " is black: nothing compared";
  }
}

TEST_F(XrCli, TheRuntimeEndsTheSessionAndTheRunEndsCleanly) {
  const cli::Result r = run("xr " + cli::cornell() + " --frames 100 --probe-samples 32 --warmup-ms 0",
                            runtime_env(std::string(R"({"eye_width": 32, "eye_height": 36, "stop_after": 8})")));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("xr: 7 frames rendered"), std::string::npos) << r.err;  // frame 0 only SYNCHRONIZED
  const json s = session();
  const std::vector<std::string> states = s["states"];
  EXPECT_EQ(std::vector<std::string>(states.end() - 3, states.end()),
            (std::vector<std::string>{"STOPPING", "IDLE", "EXITING"}));
  EXPECT_EQ(rendered(s).size(), 7u);
}

TEST_F(XrCli, LossPendingIsOneLineAndNoLeak) {
  const cli::Result r = run("xr " + cli::cornell() + " --frames 100 --probe-samples 32 --warmup-ms 0",
                            runtime_env(R"({"eye_width": 32, "eye_height": 36, "loss_after": 5})") + " DDISH_VALIDATION=1");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(count_lines(r.err, "ddish: error: "), 1) << r.err;
  EXPECT_NE(r.err.find("ddish: error: xr: the runtime lost the session (LOSS_PENDING) after 4 frames"), std::string::npos) << r.err;
  // Validation watched every destruction: nothing left alive at vkDestroyDevice / vkDestroyInstance.
  EXPECT_NE(r.err.find("xr: validation: 0 OpenXR messages, 0 Vulkan errors"), std::string::npos) << r.err;
  const std::vector<std::string> states = session()["states"];
  EXPECT_EQ(states.back(), "LOSS_PENDING");
}

// `--tracer` as on render, probes and serve (tests/app/tracer_cli_test.cpp): auto is Embree on a
// CPU device; vulkan traces the probes on the runtime's device (lavapipe 25 has ray tracing) with
// both validation layers quiet, and on a device without ray tracing is one error line and exit 2,
// as an unknown tracer is.
TEST_F(XrCli, TheTracerOptionPicksTheProbeTracer) {
  const std::string script = R"({"eye_width": 32, "eye_height": 36})";
  const cli::Result automatic = run("xr " + cli::cornell() + " --frames 2 --probe-samples 16 --grid 2,2,2 --warmup-ms 0",
                                    runtime_env(script));
  ASSERT_EQ(automatic.code, 0) << automatic.err;
  EXPECT_NE(automatic.err.find("xr: probe tracer embree (auto: "), std::string::npos) << automatic.err;
  const cli::Result bad = run("xr " + cli::cornell() + " --tracer optix", runtime_env(script));
  EXPECT_EQ(bad.code, 2);
  EXPECT_EQ(count_lines(bad.err, "ddish: error: "), 1) << bad.err;
  EXPECT_NE(bad.err.find("--tracer"), std::string::npos) << bad.err;

  const cli::Result devices = run("devices");
  const auto at = devices.out.find("[default]");
  if (at == std::string::npos || devices.out.find("ray tracing            pipelines", at) == std::string::npos) {
    // Mesa 22 lavapipe (VK_DRIVER_FILES picks it): one error line, exit 2.
    const cli::Result none = run("xr " + cli::cornell() + " --frames 2 --grid 2,2,2 --tracer vulkan", runtime_env(script));
    EXPECT_EQ(none.code, 2);
    EXPECT_EQ(count_lines(none.err, "ddish: error: --tracer vulkan: "), 1) << none.err;
    EXPECT_EQ(count_lines(none.err, "ddish: error: "), 1) << none.err;
    return;
  }
  const cli::Result gpu = run("xr " + cli::cornell() + " --frames 2 --probe-samples 16 --grid 2,2,2 --warmup-ms 0 "
                              "--tracer vulkan",
                              runtime_env(script) + " DDISH_VALIDATION=1");
  ASSERT_EQ(gpu.code, 0) << gpu.err;
  EXPECT_NE(gpu.err.find("xr: probe tracer vulkan on "), std::string::npos) << gpu.err;
  // It shares the runtime's device with the rasterizer: the traced probes are converted there.
  EXPECT_NE(gpu.err.find("xr: traced probes stay on the GPU"), std::string::npos) << gpu.err;
  EXPECT_NE(gpu.err.find("xr: validation: 0 OpenXR messages, 0 Vulkan errors"), std::string::npos) << gpu.err;
  EXPECT_EQ(rendered(session()).size(), 2u);
}

// A display period switching from 90 Hz to 72 Hz at frame 20: the budget each frame hands the
// scheduler is the frame's period, from the frame after the switch on (in the timings, both in
// the xr records and in the scheduler's own record).
TEST_F(XrCli, TheBudgetFollowsTheDisplayPeriod) {
  const std::string script = R"({"eye_width": 32, "eye_height": 36, "synchronized_frames": 0,
    "keys": [{"frame": 0, "display_hz": 90}, {"frame": 20, "display_hz": 72}]})";
  const cli::Result r = run("xr " + cli::cornell() + " --frames 30 --probe-samples 32 --warmup-ms 0 --timings " +
                                path("t.json"),
                            runtime_env(script));
  ASSERT_EQ(r.code, 0) << r.err;
  std::ifstream in(dir_ / "t.json");
  const json t = json::parse(in);
  ASSERT_EQ(t["frames"].size(), 30u);
  std::vector<double> latency;
  int within = 0;
  for (int k = 0; k < 30; ++k) {
    const double want = k < 20 ? 1000.0 / 90.0 : 1000.0 / 72.0;
    const json& x = t["frames"][k]["xr"];  // each frame's record carries its OpenXR record
    EXPECT_EQ(x["frame"].get<int>(), k);
    EXPECT_NEAR(x["predicted_display_period_ms"].get<double>(), want, 1e-3) << k;
    EXPECT_NEAR(x["budget_ms"].get<double>(), want, 1e-3) << k;
    EXPECT_NEAR(t["frames"][k]["scheduler"]["budget_ms"].get<double>(), want, 1e-3) << k;
    latency.push_back(x["pose_to_submit_ms"].get<double>());
    within += x["within_period"].get<bool>() ? 1 : 0;
  }
  // The summary line comes from a fixed-size tally, not from kept records: the same counts, and
  // the median to within its 0.1 ms bins (plus the printed digit).
  std::sort(latency.begin(), latency.end());
  const std::string head = "xr: 30 frames rendered, " + std::to_string(within) + " within the display period; pose to submit median ";
  const std::size_t at = r.err.find(head);
  ASSERT_NE(at, std::string::npos) << r.err;
  const double median = std::stod(r.err.substr(at + head.size()));
  EXPECT_NEAR(median, latency[15], 0.1 + 0.05) << r.err;
}

// Streamed probes: `ddish xr --connect` takes them from a `ddish serve` on loopback through the
// same client as `ddish view` (app/probe_setup.h), and its frames carry the stream's record.
TEST_F(XrCli, ConnectTakesTheProbesOfAServer) {
  const std::string bind = "tcp://127.0.0.1:" + std::to_string(61000 + int(getpid() % 2000) * 2);  // above the ephemeral ports (32768-60999)
  const std::string serve_log = (dir_ / "serve.log").string();
  const std::string start = cli::quote(DDISH_EXE) + " serve " + cli::cornell() + " --bind " + bind +
                            " --grid 4,4,4 --probe-samples 32 --bounces 4 --frames 2 --seconds 30 >/dev/null 2>" +
                            cli::quote(serve_log) + " & echo $! >" + path("serve.pid");
  ASSERT_EQ(std::system(start.c_str()), 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (cli::slurp(serve_log).find("update 2:") == std::string::npos && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  const cli::Result r = run("xr " + cli::cornell() + " --connect " + bind +
                                " --grid 4,4,4 --frames 3 --wait-ms 5000 --stale-ms 20000 --timings " + path("t.json"),
                            runtime_env(R"({"eye_width": 32, "eye_height": 36})"));
  const int pid = std::stoi(cli::slurp(dir_ / "serve.pid"));
  ::kill(pid, SIGTERM);
  ASSERT_EQ(r.code, 0) << r.err << cli::slurp(serve_log);
  EXPECT_NE(r.err.find("xr: probes from " + bind), std::string::npos) << r.err;
  std::ifstream in(dir_ / "t.json");
  const json t = json::parse(in);
  ASSERT_EQ(t["frames"].size(), 3u);
  EXPECT_TRUE(t["frames"][0]["stream"]["synced"].get<bool>()) << t["frames"][0].dump();
  EXPECT_EQ(t["frames"][0]["probe_updates"], 0);  // nothing traced here
  EXPECT_EQ(rendered(session()).size(), 3u);
}

}  // namespace
