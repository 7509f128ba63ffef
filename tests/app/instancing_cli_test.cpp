// EXT_mesh_gpu_instancing in both renderers: scenes/instanced_boxes.gltf (three grey cubes from
// one mesh, under the default sky) seen from the front, where the three stand side by side. Both
// renderers must draw each instance where the loader put it, and cover the same share of the
// image.
#include <string>

#include <gtest/gtest.h>

#include "cli_runner.h"
#include "metrics/image_io.h"
#include "sky_coverage.h"

namespace {

using cli::quote;
using cli::Result;

class InstancingCli : public cli::TempDirTest {
 protected:
  InstancingCli() : TempDirTest("ddish_instancing_cli_") {}
};

TEST_F(InstancingCli, RenderAndReferenceDrawEveryInstance) {
  const std::string scene = quote(std::string(DDISH_SOURCE_DIR) + "/scenes/instanced_boxes.gltf");
  // 6 m in front of the cubes' middle, 20 degree field: 30.2 px per metre at the cubes, so the
  // cubes (centres x = -1, 0, 1; 0.4, 0.57 and 0.8 m wide) land on columns 31, 61 and 91 with
  // sky between them (columns 46 and 76).
  const std::string view = " --width 128 --height 64 --camera 0.1,1.4,6,0.1,1.4,0,0,1,0 --fov 20";
  Result ref = run("reference " + scene + view + " --spp 16 --out " + path("ref"));
  ASSERT_EQ(ref.code, 0) << ref.err;
  Result render = run("render " + scene + view + " --msaa 1 --tonemap linear --out " + path("r"));
  ASSERT_EQ(render.code, 0) << render.err;
  for (const char* file : {"ref/reference.exr", "r/frame_0000.exr"}) {
    const ddish::metrics::Image img = ddish::metrics::read_image(dir_ / file);
    EXPECT_TRUE(sky_coverage::on_object(img.at(31, 38))) << file << ": first cube";
    EXPECT_TRUE(sky_coverage::on_object(img.at(61, 38))) << file << ": turned cube";
    EXPECT_TRUE(sky_coverage::on_object(img.at(91, 32))) << file << ": large cube";
    EXPECT_FALSE(sky_coverage::on_object(img.at(46, 38))) << file << ": gap";
    EXPECT_FALSE(sky_coverage::on_object(img.at(76, 38))) << file << ": gap";
  }
  const sky_coverage::Coverage r =
      sky_coverage::coverage(ddish::metrics::read_image(dir_ / "ref" / "reference.exr"));
  const sky_coverage::Coverage v =
      sky_coverage::coverage(ddish::metrics::read_image(dir_ / "r" / "frame_0000.exr"));
  // The front faces alone cover (12^2 + 17 x 12 + 24^2) / 8192 = 0.113 of the image at the
  // cubes' distance; nearer front faces and the sides that perspective shows add to it (the
  // large cube alone is 0.07). Measured: 0.136 (reference), 0.139 (render).
  EXPECT_GT(r.fraction, 0.113);
  EXPECT_LT(r.fraction, 0.16);
  EXPECT_NEAR(v.fraction, r.fraction, 0.01);
}

}  // namespace
