// The probe warm-up before the first frame (README, "No blotchy first seconds"): it runs the
// rounds its goal asks for when the bound allows, and frame 0 after it is closer to the converged
// image than frame 0 without it.
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "cli_runner.h"
#include "metrics/image_io.h"
#include "metrics/linear_error.h"

namespace {

using cli::quote;

class WarmupCli : public cli::TempDirTest {
 protected:
  WarmupCli() : TempDirTest("ddish_warmup_") {}
};

// 32x32, 4x4x4 probes at 32 samples, a 2.3 ms budget (a few probes a frame).
const std::string kRun = " --width 32 --height 32 --grid 4,4,4 --probe-samples 32 --msaa 1 --budget-ms 2.3";

TEST_F(WarmupCli, FrameZeroAfterTheWarmUpIsCloserToConverged) {
  // Converged: no budget, every active probe at 512 samples for 4 frames.
  ASSERT_EQ(run("render " + cli::cornell() + " --width 32 --height 32 --grid 4,4,4 --msaa 1 --budget-ms 0 "
                "--probe-samples 512 --frames 4 --warmup-ms 0 --out " + path("conv")).code, 0);
  const cli::Result cold = run("render " + cli::cornell() + kRun + " --warmup-ms 0 --out " + path("cold"));
  ASSERT_EQ(cold.code, 0) << cold.err;
  EXPECT_EQ(cold.err.find("warm-up:"), std::string::npos) << cold.err;
  // A bound it does not reach: exactly 128 / 32 = 4 rounds.
  const cli::Result warm =
      run("render " + cli::cornell() + kRun + " --warmup-samples 128 --warmup-ms 600000 --out " + path("warm"));
  ASSERT_EQ(warm.code, 0) << warm.err;
  EXPECT_NE(warm.err.find("render: warm-up: 4 rounds over "), std::string::npos) << warm.err;
  EXPECT_NE(warm.err.find(", 128 samples each, in "), std::string::npos) << warm.err;
  const auto ref = ddish::metrics::read_image(dir_ / "conv" / "frame_0003.exr");
  const double e_cold = ddish::metrics::rmse(ddish::metrics::read_image(dir_ / "cold" / "frame_0000.exr"), ref);
  const double e_warm = ddish::metrics::rmse(ddish::metrics::read_image(dir_ / "warm" / "frame_0000.exr"), ref);
  // Cold, frame 0 has traced only the budget's few probes; warm, every probe has 128 samples.
  // Measured: cold 0.148, warm 0.055 (0.37 of it); the bound of 0.5 leaves room for the noise
  // of 128 samples against a reference that is itself 2048 samples deep.
  std::printf("frame 0 RMSE against converged: cold %.4g, warm %.4g\n", e_cold, e_warm);
  EXPECT_LT(e_warm, 0.5 * e_cold) << "cold " << e_cold << ", warm " << e_warm;
}

TEST_F(WarmupCli, ABadBoundIsOneLineExitTwo) {
  const cli::Result r = run("render " + cli::cornell() + " --warmup-ms -5 --out " + path("o"));
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err, "ddish: error: --warmup-ms must be >= 0, got -5\n");
}

}  // namespace
