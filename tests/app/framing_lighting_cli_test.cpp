// A glTF file as users bring them, with no camera, no light and no sidecar
// (scenes/open_sphere.gltf: a grey sphere of albedo 0.5 in open space), renders with no options:
// framed from a three-quarter view (scene/framing.h), lit by the default sky
// (scene/environment_choice.h), with probes around it (ProbeGrid::fit_auto_around). And glTF's
// photometric light units through both renderers (scenes/photometric_lamp.gltf).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "cli_runner.h"
#include "metrics/image.h"
#include "metrics/image_io.h"
#include "sky_coverage.h"

namespace {

namespace fs = std::filesystem;

using cli::quote;
using cli::Result;

std::string bundled(const std::string& name) {
  return quote(std::string(DDISH_SOURCE_DIR) + "/scenes/" + name);
}

class FramingLightingCli : public cli::TempDirTest {
 protected:
  FramingLightingCli() : TempDirTest("ddish_framing_cli_") {}
  ddish::metrics::Image image(const std::string& file) const {
    return ddish::metrics::read_image(dir_ / file);
  }
};

using sky_coverage::Coverage;
using sky_coverage::coverage;

// A centred sphere whose silhouette spans 0.9 of a square image covers pi / 4 * 0.9^2 of it;
// the 32-segment mesh's polygonal silhouette is ~1 % smaller. Measured at 96 x 96: 0.630
// (reference) and 0.631 (render).
constexpr double kExpectedCoverage = std::numbers::pi / 4.0 * 0.9 * 0.9;
constexpr double kCoverageTolerance = 0.02;

TEST_F(FramingLightingCli, CameraLessLightlessSceneIsFramedLitAndSurroundedByProbes) {
  const std::string size = " --width 96 --height 96";
  Result ref = run("reference " + bundled("open_sphere.gltf") + size +
                   " --spp 64 --out " + path("ref"));
  ASSERT_EQ(ref.code, 0) << ref.err;
  EXPECT_NE(ref.err.find("no camera in the scene: framing its bounding sphere"), std::string::npos)
      << ref.err;
  EXPECT_NE(ref.err.find("default sky"), std::string::npos) << ref.err;
  Result render = run("render " + bundled("open_sphere.gltf") + size +
                      " --msaa 1 --tonemap linear --out " + path("render"));
  ASSERT_EQ(render.code, 0) << render.err;
  EXPECT_NE(render.err.find("framing its bounding sphere"), std::string::npos) << render.err;
  EXPECT_NE(render.err.find("1-cell margin"), std::string::npos) << render.err;

  const Coverage r = coverage(image("ref/reference.exr"));
  const Coverage v = coverage(image("render/frame_0000.exr"));
  EXPECT_NEAR(r.fraction, kExpectedCoverage, kCoverageTolerance);
  EXPECT_NEAR(v.fraction, kExpectedCoverage, kCoverageTolerance);
  // The sky is radiance 1 wherever the sphere is not (both renderers draw it as the background).
  EXPECT_NEAR(r.background_mean, 1.0, 0.02);
  EXPECT_NEAR(v.background_mean, 1.0, 0.02);
  // Under a uniform sky an albedo-0.5 sphere has radiance about 0.5 (its own dielectric layer
  // adds a little); the probes around it carry that sky to the raster. Without the margin
  // (--grid 16,16,16 over the sphere's own bounds) 2176 of 4096 probes are inside it and the
  // render is 15.3 dB off the reference instead of 34.0 dB: the sphere's mean then drops far
  // below the reference's. Measured: reference 0.513, render 0.494 (background 0.992 and 1: the
  // reference's pixel filter blends the sphere's edge into the pixels beside it).
  EXPECT_NEAR(r.object_mean, 0.5, 0.06);
  EXPECT_NEAR(v.object_mean, r.object_mean, 0.03);
}

TEST_F(FramingLightingCli, InfoReportsTheFramingCameraAndTheDefaultSky) {
  Result r = run("info " + bundled("open_sphere.gltf"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("view camera framing: eye"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("default sky (the scene has no light)"), std::string::npos) << r.out;
  r = run("info --json " + bundled("open_sphere.gltf"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("\"framed\": true"), std::string::npos) << r.out;
}

TEST_F(FramingLightingCli, SkyOptionWinsAndIsChecked) {
  // --sky 0,0,0 switches the default sky off: nothing lights the sphere, the image is black.
  Result r = run("reference " + bundled("open_sphere.gltf") +
                 " --width 16 --height 16 --spp 1 --sky 0,0,0 --out " + path("dark"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("environment (0, 0, 0) radiance: --sky"), std::string::npos) << r.err;
  const ddish::metrics::Image dark = image("dark/reference.exr");
  for (const glm::vec3& p : dark.pixels()) ASSERT_EQ(p, glm::vec3(0.0f));
  // A sky on a scene whose sidecar says 0 (cornell_box): the command line wins.
  r = run("probes " + bundled("cornell_box.gltf") + " --grid 2,2,2 --probe-samples 4 --sky 0.5,0.5,0.5");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("environment (0.5, 0.5, 0.5) radiance: --sky"), std::string::npos) << r.out;
  for (const char* bad : {"1,2", "1,2,3,4", "a,b,c", "1,-1,1", "1,,1", "1,2,3,", "inf,1,1"}) {
    r = run("render " + bundled("open_sphere.gltf") + " --sky " + quote(bad) + " --out " +
            path("bad"));
    EXPECT_EQ(r.code, 2) << bad;
    EXPECT_EQ(r.err.rfind("ddish: error: --sky", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

TEST_F(FramingLightingCli, ExposureScalesTheDisplayImageOnly) {
  // Sky 1 behind the sphere: one stop down shows it at display value 0.5 (the PNG reads back
  // linear); the EXR keeps radiance 1.
  Result r = run("render " + bundled("open_sphere.gltf") +
                 " --width 16 --height 16 --msaa 1 --tonemap linear --no-indirect --exposure -1 "
                 "--out " + path("ev"));
  ASSERT_EQ(r.code, 0) << r.err;
  const glm::vec3 corner_png = image("ev/frame_0000.png").at(0, 0);
  const glm::vec3 corner_exr = image("ev/frame_0000.exr").at(0, 0);
  EXPECT_NEAR(corner_exr.g, 1.0f, 1e-3f);
  EXPECT_NEAR(corner_png.g, 0.5f, 0.01f);  // 8-bit sRGB steps near 0.5 are ~0.4 %
  r = run("reference " + bundled("open_sphere.gltf") +
          " --width 8 --height 8 --spp 1 --exposure 1 --out " + path("evref"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NEAR(image("evref/reference.exr").at(0, 0).g, 1.0f, 1e-3f);
  EXPECT_NEAR(image("evref/reference.png").at(0, 0).g, 1.0f, 1e-3f);  // 2, clamped
  EXPECT_EQ(run("render " + bundled("open_sphere.gltf") + " --exposure x --out " + path("b")).code, 2);
}

// scenes/photometric_lamp.gltf: 683 cd (no sidecar, so glTF's candela) 2 m above a white floor of
// albedo 0.8 is 1 W/sr and E = 0.25 W/m^2 at its foot, where the camera looks: the floor's
// radiance there is E f(n, n) (tests/trace/photometric_light_test.cpp asserts the path tracer
// to float precision; Lambert alone would be 0.8 E / pi = 0.0637). The rasterizer's direct light
// must agree with the reference: measured 0.06409 in both.
TEST_F(FramingLightingCli, PhotometricLampAgreesInRenderAndReference) {
  const std::string size = " --width 8 --height 8";
  Result ref = run("reference " + bundled("photometric_lamp.gltf") + size +
                   " --spp 16 --bounces 2 --out " + path("ref"));
  ASSERT_EQ(ref.code, 0) << ref.err;
  EXPECT_NE(ref.err.find("environment (0, 0, 0) radiance: none"), std::string::npos) << ref.err;
  Result render = run("render " + bundled("photometric_lamp.gltf") + size +
                      " --msaa 1 --tonemap linear --no-indirect --out " + path("render"));
  ASSERT_EQ(render.code, 0) << render.err;
  const glm::vec3 r = image("ref/reference.exr").at(4, 4);
  const glm::vec3 v = image("render/frame_0000.exr").at(4, 4);
  EXPECT_NEAR(r.g, 0.8f * 0.25f / std::numbers::pi_v<float>, 0.08f * r.g);
  EXPECT_NEAR(v.g, r.g, 0.03f * r.g);
  Result info = run("info " + bundled("photometric_lamp.gltf"));
  EXPECT_NE(info.out.find("photometric (glTF): candela, lux; / 683 lm/W"), std::string::npos)
      << info.out;
  EXPECT_NE(info.out.find("intensity 1 (radiometric)"), std::string::npos) << info.out;
}

}  // namespace
