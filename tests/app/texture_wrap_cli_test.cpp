// glTF sampler wrap modes in both renderers: scenes/clamped_texture.gltf's unlit panel runs u
// from -1 to 2 over a 2 x 2 texture (red left column, blue right) with wrapS CLAMP_TO_EDGE, and
// fills a 96 x 32 view edge to edge: pixel column x sees u = -1 + 3 (x + 0.5) / 96. Clamped,
// u < 0 is the red edge texel and u > 1 the blue one; REPEAT wraps u = -0.27 to 0.73 (97 %
// blue) and u = -0.86 to 0.14 (22 % blue, filtered with the wrapped blue texel: measured with
// the rasterizer's old single REPEAT sampler, red 0.78 and blue 0.22 there).
#include <string>

#include <gtest/gtest.h>

#include "cli_runner.h"
#include "metrics/image_io.h"

namespace {

using cli::quote;
using cli::Result;

class TextureWrapCli : public cli::TempDirTest {
 protected:
  TextureWrapCli() : TempDirTest("ddish_texture_wrap_cli_") {}
};

TEST_F(TextureWrapCli, ClampedEdgesShowTheEdgeTexelsInBothRenderers) {
  const std::string scene = quote(std::string(DDISH_SOURCE_DIR) + "/scenes/clamped_texture.gltf");
  const std::string size = " --width 96 --height 32";
  Result ref = run("reference " + scene + size + " --spp 4 --out " + path("ref"));
  ASSERT_EQ(ref.code, 0) << ref.err;
  Result render = run("render " + scene + size + " --msaa 1 --tonemap linear --grid 2,2,2 --out " +
                      path("r"));
  ASSERT_EQ(render.code, 0) << render.err;
  for (const char* file : {"ref/reference.exr", "r/frame_0000.exr"}) {
    const ddish::metrics::Image img = ddish::metrics::read_image(dir_ / file);
    for (int x : {4, 23}) {  // u = -0.86, -0.27: left of the texture
      const glm::vec3 c = img.at(x, 16);
      EXPECT_NEAR(c.r, 1.0f, 0.01f) << file << " column " << x;
      EXPECT_NEAR(c.b, 0.0f, 0.01f) << file << " column " << x;
    }
    for (int x : {72, 91}) {  // u = 1.27, 1.86: right of it
      const glm::vec3 c = img.at(x, 16);
      EXPECT_NEAR(c.r, 0.0f, 0.01f) << file << " column " << x;
      EXPECT_NEAR(c.b, 1.0f, 0.01f) << file << " column " << x;
    }
  }
}

}  // namespace
