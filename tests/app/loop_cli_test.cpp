// --loop: the scene time wraps at the animation's duration. scenes/cornell_light.gltf's lamp
// (STEP keys: at A from 0 s, in its housing from 14 s, at B from 24 s, the last key) lights the
// room directly, so with --no-indirect each image is its pose alone: after t = 20 s (lamp off)
// at 0.25 fps comes t = 24 = 0 (lamp at A), identical to a render at --time 0; without --loop
// it is t = 24 (lamp at B).
#include <string>

#include <gtest/gtest.h>

#include "cli_runner.h"

namespace {

using cli::quote;
using cli::Result;

class LoopCli : public cli::TempDirTest {
 protected:
  LoopCli() : TempDirTest("ddish_loop_cli_") {}
};

TEST_F(LoopCli, SceneTimeWrapsAtTheAnimationsDuration) {
  const std::string scene = quote(std::string(DDISH_SOURCE_DIR) + "/scenes/cornell_light.gltf");
  const std::string common = scene + " --width 24 --height 24 --msaa 1 --no-indirect --tonemap linear";
  Result looped = run("render " + common + " --loop --time 20 --fps 0.25 --frames 2 --every --out " +
                      path("loop"));
  ASSERT_EQ(looped.code, 0) << looped.err;
  EXPECT_NE(looped.err.find("frame 1/2 t=20.000 s"), std::string::npos) << looped.err;
  EXPECT_NE(looped.err.find("frame 2/2 t=0.000 s"), std::string::npos) << looped.err;
  Result plain = run("render " + common + " --time 20 --fps 0.25 --frames 2 --out " + path("plain"));
  ASSERT_EQ(plain.code, 0) << plain.err;
  EXPECT_NE(plain.err.find("frame 2/2 t=24.000 s"), std::string::npos) << plain.err;
  Result start = run("render " + common + " --out " + path("start"));
  ASSERT_EQ(start.code, 0) << start.err;
  // The wrapped frame is the t = 0 pose exactly: the same image.
  Result cmp = run("compare " + path("loop/frame_0001.exr") + " " + path("start/frame_0000.exr"));
  ASSERT_EQ(cmp.code, 0) << cmp.err;
  EXPECT_NE(cmp.out.find("psnr    inf"), std::string::npos) << cmp.out;
  // ... and not the t = 20 one (the lamp in its housing).
  cmp = run("compare " + path("loop/frame_0000.exr") + " " + path("start/frame_0000.exr"));
  ASSERT_EQ(cmp.code, 0) << cmp.err;
  EXPECT_EQ(cmp.out.find("psnr    inf"), std::string::npos) << cmp.out;
}

}  // namespace
