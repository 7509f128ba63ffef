// Past one server, as processes on loopback: two `ddish serve --bricks I/2` of the Cornell box
// (8 x 4 x 4 probes: two bricks, left and right), a `ddish relay` in front of them, and `ddish
// view` clients. A client of the whole room through the relay renders exactly what the
// in-process `ddish render` renders (fp16: the same probes, traced by two servers instead of
// one); a client looking at the left wall subscribes to the left brick alone, takes its
// snapshot from its server only, and still renders exactly the in-process image of its view.
// Every process runs with --seconds, ports differ per test process (tests/app/serve_process.h).
#include <signal.h>

#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cli_runner.h"
#include "serve_process.h"

namespace {

using cli::count_in;
using cli::Process;
using cli::quote;
using cli::wait_for;

const std::string kProbes = "--grid 8,4,4 --probe-samples 16 --bounces 2 --schedule uniform";
const std::string kImage = "--width 40 --height 40 --msaa 1";
const std::string kLeftWall = "--camera -0.5,1,0,-1,1,0,0,1,0";

// Ports 8-9 of serve_process.h's per-process block (the other tests use 0-6).
std::string port(int k) { return cli::address(7 + k); }

double psnr_of(const cli::Result& r) {
  const std::size_t at = r.out.find("psnr");
  if (at == std::string::npos) return -1.0;
  const std::string v = r.out.substr(at + 4, r.out.find("dB", at) - at - 4);
  return v.find("inf") != std::string::npos ? 1e9 : std::stod(v);
}

class ServeBricks : public cli::TempDirTest {
 protected:
  ServeBricks() : TempDirTest("ddish_bricks_") {}
};

TEST_F(ServeBricks, TwoServersAndARelayRenderWhatOneProcessRenders) {
  const std::string s0 = port(0), s1 = port(1), relay = port(2);
  std::vector<std::unique_ptr<Process>> servers;
  for (int k = 0; k < 2; ++k) {
    std::vector<std::string> args = {"serve", std::string(DDISH_SOURCE_DIR) + "/scenes/cornell_box.gltf", "--bind", k == 0 ? s0 : s1, "--bricks",
                                     std::to_string(k) + "/2", "--frames", "3", "--seconds", "30",
                                     "--encoding", "fp16", "--delta-threshold", "0", "--moment-threshold", "0"};
    for (const char* a : {"--grid", "8,4,4", "--probe-samples", "16", "--bounces", "2", "--schedule", "uniform"})
      args.push_back(a);
    servers.push_back(std::make_unique<Process>(args, dir_ / ("serve" + std::to_string(k))));
  }
  Process relay_process({"relay", "--connect", s0 + "," + s1, "--bind", relay, "--seconds", "30"}, dir_ / "relay");
  for (const std::string& what : {std::string("render"), std::string("left")})
    // With distance moments on both sides (the default 8x8 maps): the relay forwards them.
    ASSERT_EQ(run("render " + cli::cornell() + " " + kProbes + " " + kImage +
                  " --frames 3 --warmup-ms 0" +
                  (what == "left" ? " " + kLeftWall : "") + " --out " + quote((dir_ / what).string())).code, 0);
  for (int k = 0; k < 2; ++k)
    ASSERT_TRUE(wait_for(dir_ / ("serve" + std::to_string(k)), "update 3:", 20.0)) << cli::slurp(dir_ / ("serve" + std::to_string(k)));
  EXPECT_NE(cli::slurp(dir_ / "serve0").find("bricks 0/2: 1 of 2"), std::string::npos) << cli::slurp(dir_ / "serve0");
  ASSERT_TRUE(wait_for(dir_ / "relay", "relay: on", 10.0));

  // The whole room, frames through the relay: both bricks, one snapshot from each server.
  const cli::Result room = run("view " + cli::cornell() + " --grid 8,4,4 " + kImage + " --connect " + s0 + "," + s1 +
                               " --relay " + relay + " --out " + quote((dir_ / "room").string()));
  ASSERT_EQ(room.code, 0) << room.err;
  EXPECT_NE(room.err.find("probes from " + s0 + ": snapshot of frame "), std::string::npos) << room.err;
  EXPECT_NE(room.err.find("probes from " + s1 + ": snapshot of frame "), std::string::npos) << room.err;
  const cli::Result c = run("compare " + quote((dir_ / "room/frame_0000.exr").string()) + " " +
                            quote((dir_ / "render/frame_0002.exr").string()));
  ASSERT_EQ(c.code, 0) << c.err;
  EXPECT_GE(psnr_of(c), 1e9) << c.out;  // identical

  // The left wall, direct: brick 0 alone, from server 0 alone, and still the in-process image.
  const cli::Result left = run("view " + cli::cornell() + " --grid 8,4,4 " + kImage + " " + kLeftWall + " --connect " +
                               s0 + "," + s1 + " --out " + quote((dir_ / "left_view").string()));
  ASSERT_EQ(left.code, 0) << left.err;
  EXPECT_NE(left.err.find("probes from " + s0 + ": snapshot of frame "), std::string::npos) << left.err;
  EXPECT_EQ(left.err.find("probes from " + s1), std::string::npos) << left.err;  // nothing of server 1
  const cli::Result l = run("compare " + quote((dir_ / "left_view/frame_0000.exr").string()) + " " +
                            quote((dir_ / "left/frame_0002.exr").string()));
  ASSERT_EQ(l.code, 0) << l.err;
  EXPECT_GE(psnr_of(l), 1e9) << l.out;

  // The relay stops by itself and says what it forwarded.
  EXPECT_EQ(relay_process.stop(SIGTERM, 5.0), 0);
  EXPECT_NE(cli::slurp(dir_ / "relay").find("subscription messages upstream"), std::string::npos);
}

TEST_F(ServeBricks, BadOptionsExit2) {
  for (const std::string& bad : {std::string("serve ") + cli::cornell() + " --bricks 2/2",
                                 std::string("serve ") + cli::cornell() + " --bricks x",
                                 std::string("relay --connect tcp://127.0.0.1:1 --bind tcp://10.0.0.1:5600"),
                                 std::string("relay --connect tcp://127.0.0.1:1,tcp://127.0.0.1:1"),
                                 std::string("view ") + cli::cornell() + " --connect tcp://127.0.0.1:1,nope"}) {
    const cli::Result r = run(bad);
    EXPECT_EQ(r.code, 2) << bad;
    EXPECT_NE(r.err.find("ddish: error: "), std::string::npos) << bad << "\n" << r.err;
  }
}

}  // namespace
