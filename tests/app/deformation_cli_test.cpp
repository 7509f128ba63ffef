// Skins and morph targets in both renderers. The render runs two frames, so the second one is
// posed after the tracer's Embree scene and the rasterizer's vertex buffer were built: the
// probes' tracer refits the deformed mesh and the rasterizer re-uploads it. Its image must show
// the same pose as a reference traced at that time.
#include <string>

#include <gtest/gtest.h>

#include "cli_runner.h"
#include "metrics/image_io.h"
#include "sky_coverage.h"

namespace {

using cli::quote;
using cli::Result;

class DeformationCli : public cli::TempDirTest {
 protected:
  DeformationCli() : TempDirTest("ddish_deformation_cli_") {}

  // scenes/NAME at 128 x 96 through `reference` (into ref/) and `render` (into r/), each with its
  // own options; returns `ddish info`'s text, checked for the deformed-mesh count line `counts`.
  std::string run_both(const std::string& name, const std::string& ref_args, const std::string& render_args,
                       const std::string& counts) {
    const std::string scene = quote(std::string(DDISH_SOURCE_DIR) + "/scenes/" + name);
    const std::string size = " --width 128 --height 96";
    Result ref = run("reference " + scene + size + ref_args + " --out " + path("ref"));
    EXPECT_EQ(ref.code, 0) << ref.err;
    Result render = run("render " + scene + size + render_args + " --out " + path("r"));
    EXPECT_EQ(render.code, 0) << render.err;
    Result info = run("info " + scene);
    EXPECT_EQ(info.code, 0) << info.err;
    EXPECT_NE(info.out.find(counts), std::string::npos) << info.out;
    return info.out;
  }
};

// scenes/skinned_bar.gltf at 128 x 96: 40.7 px per metre at the bar's front faces (z = 0.1,
// 5.9 m from the camera at x = -0.45, y = 1). Pixel (58, 48) is the bent upper half at
// (-0.6, 1.0), (82, 24) the upright one at (0, 1.6), (82, 68) the lower half at (0, 0.5).
TEST_F(DeformationCli, SkinnedBarBendsInRenderAndReference) {
  // Render frame 0 at t = 0 (rest), frame 1 at t = 1 (bent).
  const std::string info = run_both("skinned_bar.gltf", " --time 1 --spp 16",
                                    " --frames 2 --fps 1 --every --msaa 1 --tonemap linear",
                                    "deformed    1 skinned, 0 morphed mesh");
  ASSERT_FALSE(HasFailure());
  EXPECT_EQ(info.find("ignored"), std::string::npos) << info;

  const ddish::metrics::Image rest = ddish::metrics::read_image(dir_ / "r" / "frame_0000.exr");
  EXPECT_FALSE(sky_coverage::on_object(rest.at(58, 48)));
  EXPECT_TRUE(sky_coverage::on_object(rest.at(82, 24)));
  for (const char* file : {"ref/reference.exr", "r/frame_0001.exr"}) {
    const ddish::metrics::Image img = ddish::metrics::read_image(dir_ / file);
    EXPECT_TRUE(sky_coverage::on_object(img.at(58, 48))) << file << ": bent half";
    EXPECT_FALSE(sky_coverage::on_object(img.at(82, 24))) << file << ": where the upright half was";
    EXPECT_TRUE(sky_coverage::on_object(img.at(82, 68))) << file << ": lower half";
  }
  const sky_coverage::Coverage r =
      sky_coverage::coverage(ddish::metrics::read_image(dir_ / "ref" / "reference.exr"));
  const sky_coverage::Coverage v =
      sky_coverage::coverage(ddish::metrics::read_image(dir_ / "r" / "frame_0001.exr"));
  // The bent bar's front faces: 0.39 m^2 of the 3.2 x 2.4 m view at z = 0, 0.0508 of the
  // image, 0.0525 at their depth (the sides perspective shows add a little, the pixels on the
  // silhouette count as object or sky). Measured: 0.0522 (reference), 0.0514 (render).
  EXPECT_GT(r.fraction, 0.048);
  EXPECT_LT(r.fraction, 0.057);
  EXPECT_NEAR(v.fraction, r.fraction, 0.003);
}

// scenes/morph_panels.gltf at 128 x 96, 40 px per metre: columns 34 and 94 cross the left
// (default weight 0.5, top edge at y = 1.5) and right (animated: 0.25 at t = 0.5, top edge at
// 1.25) panels; rows 40, 30 and 18 are y = 1.1, 1.35 and 1.65. Unlit: the panels' pixels are
// exactly their base colour in both renderers.
TEST_F(DeformationCli, MorphedPanelsInRenderAndReference) {
  run_both("morph_panels.gltf", " --time 0.5 --spp 4", " --frames 2 --fps 2 --msaa 1 --tonemap linear --grid 2,2,2",
           "deformed    0 skinned, 2 morphed meshes");
  ASSERT_FALSE(HasFailure());

  const glm::vec3 panel(0.2f, 0.6f, 0.9f);
  auto is_panel = [&](const glm::vec3& c) { return glm::length(c - panel) < 3e-3f; };
  for (const char* file : {"ref/reference.exr", "r/frame_0001.exr"}) {
    const ddish::metrics::Image img = ddish::metrics::read_image(dir_ / file);
    EXPECT_TRUE(is_panel(img.at(34, 40))) << file;
    EXPECT_TRUE(is_panel(img.at(34, 30))) << file << ": the left panel reaches 1.5";
    EXPECT_FALSE(is_panel(img.at(34, 18))) << file;
    EXPECT_TRUE(is_panel(img.at(94, 40))) << file;
    EXPECT_FALSE(is_panel(img.at(94, 30))) << file << ": the right panel stops at 1.25";
  }
}

}  // namespace
