// `ddish serve` and `ddish view` as processes on loopback: a view's image equals the in-process
// render of the same probes, visibility and relocation included (fp16: exactly; compact: within
// its measured error), and takes the server's moment maps whatever its own options, a late joiner
// renders every probe in its first frame, a client keeps writing frames while its server is
// killed and restarted and takes a snapshot each time, a client of another scene is refused, a
// client without a server says what it renders with, and bad options exit 2. Every server runs
// with --seconds, so nothing outlives a test; ports differ per test and per process.
#include <signal.h>

#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "serve_process.h"

namespace {

using cli::quote;
using cli::address;
using cli::count_in;
using cli::Process;
using cli::wait_for;

std::string scene_path(const char* name) { return std::string(DDISH_SOURCE_DIR) + "/scenes/" + name; }

const std::vector<std::string> kProbeArgs = {"--grid", "4,4,4", "--probe-samples", "32", "--bounces", "4",
                                             "--schedule", "uniform"};
const std::string kProbeFlags = "--grid 4,4,4 --probe-samples 32 --bounces 4 --schedule uniform";
const std::string kImage = "--width 48 --height 48 --msaa 1";

std::vector<std::string> serve_args(const std::string& bind, std::vector<std::string> extra,
                                    const char* scene = "cornell_box.gltf") {
  std::vector<std::string> a = {"serve", scene_path(scene), "--bind", bind};
  a.insert(a.end(), kProbeArgs.begin(), kProbeArgs.end());
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

double psnr_of(const cli::Result& r) {
  const std::size_t at = r.out.find("psnr");
  if (at == std::string::npos) return -1.0;
  const std::string v = r.out.substr(at + 4, r.out.find("dB", at) - at - 4);
  return v.find("inf") != std::string::npos ? 1e9 : std::stod(v);
}

class ServeView : public cli::TempDirTest {
 protected:
  ServeView() : TempDirTest("ddish_serve_") {}
  nlohmann::json timings(const std::string& name) { return nlohmann::json::parse(cli::slurp(dir_ / name)); }
};

// The view renders what `ddish render` renders after the same 3 updates with the same seed,
// visibility included: every sent probe carries its relocation offset (f32) and, at
// --delta-threshold 0 and --moment-threshold 0, its distance-moment map whenever any texel of it moved at all (fp16, the
// halves the renderer uploads; the view's snapshot holds every map sent), so with fp16 coefficients the images are
// identical; the compact encoding's coefficient error (about 1% of L0 in the high bands) costs
// 58.6 dB here (measured; 57.9 dB on net_figures' 8x8x8 Cornell box), asserted >= 55 dB. A
// server without moments (--probe-visibility 0) makes the view size its volume without them
// too (its INFO reply), and the view then equals the in-process render without visibility.
TEST_F(ServeView, ViewEqualsInProcessRender) {
  // No warm-up: the view's 3 frames take the server's first 3 updates. Relocation on, so that
  // offsets travel (probes of the 4x4x4 Cornell box lie near its walls).
  for (const char* visibility : {"8", "0"})
    ASSERT_EQ(run("render " + cli::cornell() + " " + kProbeFlags + " " + kImage + " --probe-relocation" +
                  " --probe-visibility " + visibility + " --frames 3 --warmup-ms 0 --out " +
                  quote((dir_ / (std::string("render") + visibility)).string())).code, 0);
  int test = 0;
  for (const auto& [encoding, visibility] : {std::pair{"fp16", "8"}, std::pair{"compact", "8"}, std::pair{"fp16", "0"}}) {
    const std::string bind = address(test++);
    const std::string name = std::string(encoding) + "_" + visibility;
    Process server(serve_args(bind, {"--frames", "3", "--seconds", "20", "--encoding", encoding,
                                     "--delta-threshold", "0", "--moment-threshold", "0", "--probe-relocation", "--probe-visibility", visibility}),
                   dir_ / ("serve_" + name));
    ASSERT_TRUE(wait_for(dir_ / ("serve_" + name), "update 3:", 15.0));
    const std::string out = (dir_ / name).string();
    const cli::Result v = run("view " + cli::cornell() + " --grid 4,4,4 " + kImage +
                                        " --connect " + bind + " --out " + quote(out));
    ASSERT_EQ(v.code, 0) << v.err;
    EXPECT_NE(v.err.find("snapshot of frame"), std::string::npos) << v.err;
    EXPECT_NE(v.err.find(std::string(visibility) == "8" ? "the server streams 8x8 distance-moment maps"
                                                        : "the server streams no distance moments"),
              std::string::npos) << v.err;
    const cli::Result c = run("compare " + quote(out + "/frame_0000.exr") + " " +
                                        quote((dir_ / (std::string("render") + visibility) / "frame_0002.exr").string()));
    ASSERT_EQ(c.code, 0) << c.err;
    if (std::string(encoding) == "fp16")
      EXPECT_GE(psnr_of(c), 1e9) << name << ": " << c.out;
    else
      EXPECT_GE(psnr_of(c), 55.0) << name << ": " << c.out;
  }
}

// A server that moved its grid (--probe-placement fit: the Cornell box's 4x4x4 grid moves a
// quarter cell along z) describes the grid's bounds at start, and a view that is not told of the
// fit takes them: it says by how much its grid moved, its scene identity is the server's, and its
// image equals the in-process render of the fitted grid (fp16, thresholds 0: exactly).
TEST_F(ServeView, AViewTakesTheServersFittedGrid) {
  ASSERT_EQ(run("render " + cli::cornell() + " " + kProbeFlags + " " + kImage +
                " --probe-placement fit --probe-relocation --probe-visibility 8 --frames 3 --warmup-ms 0 --out " +
                quote((dir_ / "render").string())).code, 0);
  const std::string bind = address(8);
  Process server(serve_args(bind, {"--probe-placement", "fit", "--frames", "3", "--seconds", "20", "--encoding", "fp16",
                                   "--delta-threshold", "0", "--moment-threshold", "0", "--probe-relocation",
                                   "--probe-visibility", "8"}),
                 dir_ / "serve");
  ASSERT_TRUE(wait_for(dir_ / "serve", "update 3:", 15.0)) << cli::slurp(dir_ / "serve");
  const std::string out = (dir_ / "view").string();
  const cli::Result v = run("view " + cli::cornell() + " --grid 4,4,4 " + kImage + " --connect " + bind +
                            " --out " + quote(out));
  ASSERT_EQ(v.code, 0) << v.err;
  EXPECT_NE(v.err.find("probe grid 4x4x4 over the server's bounds (moved (0, 0, -0.25) cells"), std::string::npos)
      << v.err;
  EXPECT_EQ(v.err.find("probe placement: fit over"), std::string::npos) << v.err;  // no fit of its own
  EXPECT_NE(v.err.find("snapshot of frame"), std::string::npos) << v.err;
  const cli::Result c = run("compare " + quote(out + "/frame_0000.exr") + " " +
                            quote((dir_ / "render" / "frame_0002.exr").string()));
  ASSERT_EQ(c.code, 0) << c.err;
  EXPECT_GE(psnr_of(c), 1e9) << c.out;
}

// The server traces its probes in the light it is given (--sky, as render's): a view of an open
// scene served under a bright sky equals the in-process render under that sky, and not the one
// under the default sky.
TEST_F(ServeView, ServerTracesUnderItsSky) {
  const std::string scene = scene_path("open_sphere.gltf");
  const std::string sky = "--sky 2,1.5,1";
  for (const std::string& which : {std::string("bright"), std::string("default")})
    ASSERT_EQ(run("render " + quote(scene) + " " + kProbeFlags + " " + kImage +
                  " --frames 3 --warmup-ms 0 " +
                  (which == "bright" ? sky : "") + " --out " + quote((dir_ / which).string())).code, 0);
  const std::string bind = address(7);
  Process server(serve_args(bind, {"--frames", "3", "--seconds", "20", "--encoding", "fp16", "--delta-threshold", "0", "--moment-threshold", "0",
                                   "--sky", "2,1.5,1"}, "open_sphere.gltf"),
                 dir_ / "serve");
  ASSERT_TRUE(wait_for(dir_ / "serve", "update 3:", 15.0));
  EXPECT_NE(cli::slurp(dir_ / "serve").find("serve: environment (2, 1.5, 1) radiance: --sky"), std::string::npos)
      << cli::slurp(dir_ / "serve");
  const std::string out = (dir_ / "view").string();
  const cli::Result v = run("view " + quote(scene) + " --grid 4,4,4 " + kImage + " " + sky + " --connect " + bind +
                            " --out " + quote(out));
  ASSERT_EQ(v.code, 0) << v.err;
  const auto psnr_against = [&](const std::string& which) {
    const cli::Result c = run("compare " + quote(out + "/frame_0000.exr") + " " +
                              quote((dir_ / which / "frame_0002.exr").string()));
    EXPECT_EQ(c.code, 0) << c.err;
    return psnr_of(c);
  };
  EXPECT_GE(psnr_against("bright"), 1e9);
  EXPECT_LT(psnr_against("default"), 60.0);
}

TEST_F(ServeView, LateJoinerRendersEveryProbeInItsFirstFrame) {
  const std::string bind = address(2);
  Process server({"serve", scene_path("cornell_box.gltf"), "--bind", bind, "--grid", "4,4,4",
                  "--probe-samples", "8", "--bounces", "4", "--schedule", "uniform", "--frames", "200",
                  "--fps", "1000", "--seconds", "40", "--delta-threshold", "0", "--moment-threshold", "0"},
                 dir_ / "serve");
  ASSERT_TRUE(wait_for(dir_ / "serve", "update 200:", 35.0)) << cli::slurp(dir_ / "serve");
  const cli::Result v = run("view " + cli::cornell() + " --grid 4,4,4 " + kImage + " --connect " +
                                      bind + " --out " + quote((dir_ / "v").string()) + " --timings " +
                                      quote((dir_ / "t.json").string()));
  ASSERT_EQ(v.code, 0) << v.err;
  const nlohmann::json f = timings("t.json")["frames"][0];
  EXPECT_TRUE(f["stream"]["synced"].get<bool>());
  EXPECT_GE(f["stream"]["server_frame"].get<int>(), 200);
  EXPECT_EQ(f["probes_changed"].get<int>(), 64);  // the keyframe sets every probe at once
  EXPECT_EQ(f["probes_never_updated"].get<int>(), 0);
  EXPECT_GT(f["probes_active"].get<int>(), 0);
}

// The server is killed (SIGKILL) and restarted 3 times while one client renders; the client never
// stops writing frames, notices each loss and takes a snapshot of each new server. Each restart
// waits (bounded) for the client to have said so, so a slow machine only makes it slower.
TEST_F(ServeView, ClientSurvivesServerRestarts) {
  const std::string bind = address(3);
  const int frames = 240;  // at 30-50 ms a frame (--frame-wait-ms), 8-12 s: longer than the restarts
  const std::string view_cmd = "view " + cli::cornell() + " --grid 4,4,4 --width 24 --height 24 --msaa 1 --frames " +
                               std::to_string(frames) + " --every --frame-wait-ms 50 --stale-ms 300 --wait-ms 0 --connect " +
                               bind + " --out " + quote((dir_ / "v").string()) + " --timings " +
                               quote((dir_ / "t.json").string());
  const cli::fs::path view_log = dir_ / "stderr";  // run() sends the view's stderr here
  std::thread restarts([&] {
    for (std::size_t k = 0; k < 3; ++k) {
      Process server(serve_args(bind, {"--fps", "30", "--seconds", "30"}), dir_ / ("serve" + std::to_string(k)));
      for (int i = 0; i < 500 && count_in(view_log, "snapshot of frame") < k + 1; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      std::this_thread::sleep_for(std::chrono::milliseconds(300));
      server.kill(SIGKILL);
      for (int i = 0; i < 250 && count_in(view_log, "lost the probe server") < k + 1; ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  });
  const cli::Result v = run(view_cmd);
  restarts.join();
  ASSERT_EQ(v.code, 0) << v.err;
  const nlohmann::json t = timings("t.json");
  ASSERT_EQ(t["frames"].size(), std::size_t(frames));
  int pngs = 0;
  for (const auto& e : cli::fs::directory_iterator(dir_ / "v")) pngs += e.path().extension() == ".png";
  EXPECT_EQ(pngs, frames);  // a frame written every frame, server or not
  EXPECT_EQ(count_in(view_log, "lost the probe server"), 3u) << v.err;
  EXPECT_EQ(count_in(view_log, "probe server back"), 2u) << v.err;  // the first snapshot is not a return
  int synced = 0;  // frames rendered with a live server's probes
  for (const auto& f : t["frames"]) synced += f["stream"]["synced"].get<bool>();
  EXPECT_GT(synced, 10);
}

TEST_F(ServeView, ClientOfAnotherSceneIsRefused) {
  const std::string bind = address(4);
  Process server(serve_args(bind, {"--frames", "2", "--seconds", "20"}, "cornell_spot.gltf"), dir_ / "serve");
  ASSERT_TRUE(wait_for(dir_ / "serve", "update 2:", 15.0));
  const cli::Result v = run("view " + cli::cornell() + " --grid 4,4,4 " + kImage + " --frames 2 --wait-ms 1000 --connect " +
                                      bind + " --out " + quote((dir_ / "v").string()) + " --timings " +
                                      quote((dir_ / "t.json").string()));
  ASSERT_EQ(v.code, 0) << v.err;
  EXPECT_NE(v.err.find("refusing the probe server"), std::string::npos) << v.err;
  EXPECT_NE(v.err.find("another scene"), std::string::npos) << v.err;
  EXPECT_NE(v.err.find("direct light only"), std::string::npos) << v.err;
  const nlohmann::json f = timings("t.json")["frames"][1];
  EXPECT_FALSE(f["stream"]["synced"].get<bool>());
  EXPECT_GT(f["stream"]["rejected"].get<int>(), 0);
}

TEST_F(ServeView, WithoutServerRendersBakedProbesAndSaysSo) {
  const std::string volume = (dir_ / "baked.ddpv").string();
  ASSERT_EQ(run("probes " + cli::cornell() + " --grid 4,4,4 --probe-samples 32 --out " + quote(volume)).code, 0);
  const cli::Result baked = run("view " + cli::cornell() + " --grid 4,4,4 " + kImage + " --wait-ms 200 --probes " +
                                          quote(volume) + " --connect " + address(5) + " --out " + quote((dir_ / "b").string()));
  ASSERT_EQ(baked.code, 0) << baked.err;
  EXPECT_NE(baked.err.find("no probe server at"), std::string::npos) << baked.err;
  EXPECT_NE(baked.err.find("baked probes of"), std::string::npos) << baked.err;
  const cli::Result direct = run("view " + cli::cornell() + " --grid 4,4,4 " + kImage + " --wait-ms 400 --connect " +
                                           address(5) + " --out " + quote((dir_ / "d").string()) + " --timings " +
                                           quote((dir_ / "t.json").string()));
  ASSERT_EQ(direct.code, 0) << direct.err;
  EXPECT_NE(direct.err.find("direct light only"), std::string::npos) << direct.err;
  // --wait-ms bounds the stream description's wait and the first frame's together: the
  // description took all 400 ms, so the first frame does not wait again (it waited another
  // 400 ms before; a poll that does not wait takes well under a millisecond).
  EXPECT_LT(timings("t.json")["frames"][0]["stages_ms"]["probe_receive"].get<double>(), 200.0);
  const cli::Result c = run("compare " + quote((dir_ / "b/frame_0000.exr").string()) + " " +
                                      quote((dir_ / "d/frame_0000.exr").string()));
  EXPECT_LT(psnr_of(c), 60.0) << c.out;  // the baked probes add light
  const cli::Result wrong = run("view " + cli::cornell() + " --grid 2,2,2 " + kImage + " --probes " +
                                          quote(volume) + " --connect " + address(5));
  EXPECT_EQ(wrong.code, 2);
  EXPECT_NE(wrong.err.find("ddish: error: --probes"), std::string::npos) << wrong.err;
}

// CurveZMQ end to end: the listed client key is served, an unknown one gets nothing (the
// server's ZAP handler refuses it) and renders direct light only.
TEST_F(ServeView, CurveServesListedKeysOnly) {
  const std::string keys = (dir_ / "keys").string(), allowed = (dir_ / "allowed").string();
  for (const char* name : {"server", "client", "stranger"})
    ASSERT_EQ(run("keys --out " + quote(keys) + " --name " + name).code, 0);
  cli::fs::create_directories(allowed);
  cli::fs::copy_file(keys + "/client.pub", allowed + "/client.pub");
  EXPECT_EQ(cli::slurp(keys + "/server.pub").size(), 41u);  // 40 Z85 characters and a newline
  EXPECT_EQ(cli::fs::status(keys + "/server.key").permissions() & cli::fs::perms::others_read, cli::fs::perms::none);
  const std::string bind = address(6);
  Process server(serve_args(bind, {"--frames", "2", "--seconds", "20", "--curve-secret", keys + "/server.key",
                                   "--allow-keys", allowed}),
                 dir_ / "serve");
  ASSERT_TRUE(wait_for(dir_ / "serve", "update 2:", 15.0)) << cli::slurp(dir_ / "serve");
  const std::string view = "view " + cli::cornell() + " --grid 4,4,4 " + kImage + " --wait-ms 1500 --connect " + bind +
                           " --curve-server-key " + quote(keys + "/server.pub") + " --curve-secret ";
  const cli::Result ok = run(view + quote(keys + "/client.key") + " --out " + quote((dir_ / "ok").string()));
  ASSERT_EQ(ok.code, 0) << ok.err;
  EXPECT_NE(ok.err.find("snapshot of frame"), std::string::npos) << ok.err;
  const cli::Result refused = run(view + quote(keys + "/stranger.key") + " --out " + quote((dir_ / "no").string()));
  ASSERT_EQ(refused.code, 0) << refused.err;
  EXPECT_EQ(refused.err.find("snapshot of frame"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("direct light only"), std::string::npos) << refused.err;
  EXPECT_TRUE(wait_for(dir_ / "serve", "refused a client whose key is not allowed", 5.0)) << cli::slurp(dir_ / "serve");
}

// --client-budget-ms: the tick's budget is one client's per connected client (at least one),
// capped by --budget-ms; the tick records say which budget each update had.
TEST_F(ServeView, ClientBudgetScalesWithClientsWithinTheTickBudget) {
  for (const auto& [extra, expected] : {std::pair{std::string("--client-budget-ms 7"), 7.0},
                                        std::pair{std::string("--client-budget-ms 7 --budget-ms 5"), 5.0},
                                        std::pair{std::string("--budget-ms 6"), 6.0}}) {
    const std::string t = (dir_ / "t.json").string();
    const cli::Result r = run("serve " + cli::cornell() + " --grid 4,4,4 --probe-samples 32 --bounces 4 --frames 3 "
                              "--seconds 4 --bind " + address(9) + " --timings " + quote(t) + " " + extra);
    ASSERT_EQ(r.code, 0) << r.err;
    int updated = 0;
    const nlohmann::json record = timings("t.json");
    for (const auto& tick : record["ticks"])
      if (tick["updated"].get<bool>()) {
        EXPECT_DOUBLE_EQ(tick["budget_ms"].get<double>(), expected) << extra;
        ++updated;
      }
    EXPECT_GE(updated, 1) << extra;  // --seconds may end a slow (sanitizer) run before all 3
  }
}

TEST_F(ServeView, BadOptionsExitTwoWithOneLine) {
  const std::string scene = cli::cornell();
  for (const std::string& args :
       {"serve " + scene + " --bind tcp://0.0.0.0:5570 --seconds 1",
        "serve " + scene + " --bind 127.0.0.1:5570 --seconds 1",
        "serve " + scene + " --bind tcp://127.0.0.1:65535 --seconds 1",
        "serve " + scene + " --encoding fp8 --seconds 1",
        "serve " + scene + " --delta-threshold -1 --seconds 1",
        "serve " + scene + " --moment-threshold nan --seconds 1",
        "serve " + scene + " --client-budget-ms -2 --seconds 1",
        "serve " + scene + " --sky 1,2 --seconds 1",
        "view " + scene + " --connect nowhere",
        "view " + scene + " --connect tcp://127.0.0.1:5570 --stale-ms 0",
        "serve " + scene + " --curve-secret " + scene + " --seconds 1",
        "keys --out " + quote((dir_ / "k").string()) + " --name a/b"}) {
    const cli::Result r = run(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("ddish: error: ", 0), 0u) << args << "\n" << r.err;
  }
}

}  // namespace
