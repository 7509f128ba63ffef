// `ddish render` output through the writer thread (app/output_queue.h): every frame of an --every
// run is written, each with its own frame's pixels (not a later frame's buffer), and the last
// frame's timings hold the wait for the writer.
#include <string>

#include <nlohmann/json.hpp>

#include "display_cli.h"
#include "metrics/image_io.h"

namespace {

using namespace display_cli;
namespace metrics = ddish::metrics;

class RenderOutputCli : public Cli {};

TEST_F(RenderOutputCli, EveryFrameIsWrittenWithItsOwnPixels) {
  // The animated box moves between frames, so frames differ and a mix-up would show.
  const std::string scene = quote(std::string(DDISH_SOURCE_DIR) + "/scenes/cornell_animated.gltf");
  // No warm-up: a warm-up cut short by its time bound would differ between the two runs.
  const std::string common = " --width 24 --height 24 --probe-samples 8 --msaa 1 --fps 4 --warmup-ms 0";
  Result all = run("render " + scene + common + " --frames 3 --every --out " + path("every") +
                   " --timings " + path("every.json"));
  ASSERT_EQ(all.code, 0) << all.err;
  for (int k = 0; k < 3; ++k)
    for (const char* ext : {".png", ".exr"}) {
      const fs::path f = dir_ / "every" / ("frame_000" + std::to_string(k) + ext);
      EXPECT_TRUE(fs::is_regular_file(f)) << f;
      EXPECT_NE(all.out.find(f.string()), std::string::npos) << "not reported: " << f;
    }
  EXPECT_TRUE(slurp(dir_ / "every/frame_0000.png") != slurp(dir_ / "every/frame_0002.png"));
  // Frame 2 alone (the same seed and probe updates): the same bytes as frame 2 of the --every run.
  Result last = run("render " + scene + common + " --frames 3 --out " + path("last"));
  ASSERT_EQ(last.code, 0) << last.err;
  EXPECT_FALSE(fs::exists(dir_ / "last/frame_0000.png"));
  EXPECT_TRUE(slurp(dir_ / "last/frame_0002.png") == slurp(dir_ / "every/frame_0002.png"));
  // EXR headers carry the time of writing, so the pixels are compared.
  EXPECT_EQ(metrics::read_image(dir_ / "last/frame_0002.exr").pixels(),
            metrics::read_image(dir_ / "every/frame_0002.exr").pixels());

  const nlohmann::json doc = nlohmann::json::parse(slurp(dir_ / "every.json"));
  ASSERT_EQ(doc["frames"].size(), 3u);
  for (int k = 0; k < 3; ++k) {
    const auto& stages = doc["frames"][std::size_t(k)]["stages_ms"];
    EXPECT_TRUE(stages.contains("output")) << k;
    EXPECT_EQ(stages.contains("output_drain"), k == 2) << k;
  }
}

}  // namespace
