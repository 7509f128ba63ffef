// KHR_materials_unlit in both renderers: scenes/unlit_panel.gltf's panel (base colour
// (0.2, 0.6, 0.9)) fills the view while a 5 W/m^2 sun shines on it head-on. Unlit, both the
// path tracer and the rasterizer (with its probes) show exactly the base colour; lit, a diffuse
// panel of that colour would read about 5 x 0.6 / pi = 0.95 in green.
#include <string>

#include <gtest/gtest.h>

#include "cli_runner.h"
#include "metrics/image_io.h"

namespace {

using cli::quote;
using cli::Result;

class UnlitCli : public cli::TempDirTest {
 protected:
  UnlitCli() : TempDirTest("ddish_unlit_cli_") {}
};

TEST_F(UnlitCli, BothRenderersShowTheBaseColour) {
  const std::string scene = quote(std::string(DDISH_SOURCE_DIR) + "/scenes/unlit_panel.gltf");
  const std::string size = " --width 16 --height 16";
  Result ref = run("reference " + scene + size + " --spp 4 --out " + path("ref"));
  ASSERT_EQ(ref.code, 0) << ref.err;
  Result render = run("render " + scene + size + " --msaa 1 --tonemap linear --grid 2,2,2 --out " +
                      path("r"));
  ASSERT_EQ(render.code, 0) << render.err;
  Result info = run("info " + scene);
  EXPECT_EQ(info.out.find("KHR_materials_unlit"), std::string::npos) << info.out;  // no warning
  const glm::vec3 want(0.2f, 0.6f, 0.9f);
  for (const char* file : {"ref/reference.exr", "r/frame_0000.exr"}) {
    const ddish::metrics::Image img = ddish::metrics::read_image(dir_ / file);
    for (const auto& [x, y] : {std::pair{8, 8}, std::pair{1, 1}, std::pair{14, 3}}) {
      const glm::vec3 c = img.at(x, y);
      for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(c[k], want[k], 2e-3f) << file << " pixel " << x << "," << y << " channel " << k;
    }
  }
}

}  // namespace
