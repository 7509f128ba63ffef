// Image-based lighting from the command line: `--environment FILE.exr|.hdr` with
// `--environment-rotation` and `--environment-intensity`, through `reference` (the path tracer
// importance-samples the map), `render` (the probes carry it; a background pass draws it) and
// `probes`, on scenes/environment_plane.gltf (a Lambertian floor, albedo 0.5, camera 0.5 m above
// it looking along -Z with a 60 degree field). The maps are written here.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "cli_runner.h"
#include "metrics/image.h"
#include "metrics/image_io.h"

namespace {

namespace fs = std::filesystem;
using cli::quote;
using cli::Result;
using ddish::metrics::Image;

const std::string kPlane = quote(std::string(DDISH_SOURCE_DIR) + "/scenes/environment_plane.gltf");
constexpr float kAlbedo = 0.5f;  // scripts/feature_scenes.py ENVIRONMENT_PLANE_ALBEDO
const std::string kSize = " --width 32 --height 32";
// The render's probes: the automatic grid over the floor's bounds and their one-cell margin,
// 16 x 2 x 16, one layer above the floor and one below it (inside: it sees the floor's back).
// (An explicit --grid spans the floor's own, flat bounds: every probe would lie in it.)
const std::string kRender = " --msaa 1 --tonemap linear";

// Upper hemisphere kSky, lower kAlbedo * kSky: what the floor itself reflects, so a probe above
// the floor sees an exact two-hemisphere step, whose irradiance L1 SH holds exactly.
const glm::vec3 kSky(1.0f, 0.8f, 0.6f);

Image equirect(int height, const std::function<glm::vec3(int, int)>& texel) {
  Image im(2 * height, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < 2 * height; ++x) im.at(x, y) = texel(x, y);
  return im;
}

void write_hdr(const fs::path& path, const Image& image) {
  auto out = OIIO::ImageOutput::create(path.string());
  ASSERT_TRUE(out);
  OIIO::ImageSpec spec(image.width(), image.height(), 3, OIIO::TypeDesc::FLOAT);
  ASSERT_TRUE(out->open(path.string(), spec));
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, image.pixels().data()));
  out->close();
}

// Mean over rows [y0, y1) and columns [x0, x1).
glm::dvec3 mean(const Image& im, int x0, int x1, int y0, int y1) {
  glm::dvec3 s(0.0);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) s += glm::dvec3(im.at(x, y));
  return s / double((x1 - x0) * (y1 - y0));
}

class EnvironmentCli : public cli::TempDirTest {
 protected:
  EnvironmentCli() : TempDirTest("ddish_environment_cli_") {}
  Image image(const std::string& file) const { return ddish::metrics::read_image(dir_ / file); }
  int lines(const std::string& text) const {
    return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  }
};

// 32 x 32 at a 60 degree field: rows 0..9 look more than 13 degrees above the horizon (sky,
// clear of the horizon row's bilinear blur), rows 24..31 more than 16 degrees below it (floor).
constexpr int kSkyRows = 10;
constexpr int kFloorRow = 24;

TEST_F(EnvironmentCli, FloorUnderTwoHemispheresHasTheAnalyticRadianceInBothRenderers) {
  ddish::metrics::write_exr(dir_ / "sky.exr", equirect(32, [](int, int y) {
                              return y < 16 ? kSky : kAlbedo * kSky;
                            }));
  Result ref = run("reference " + kPlane + kSize + " --spp 64 --environment " + path("sky.exr") +
                   " --out " + path("ref"));
  ASSERT_EQ(ref.code, 0) << ref.err;
  EXPECT_NE(ref.err.find("environment map"), std::string::npos) << ref.err;
  Result render = run("render " + kPlane + kSize + kRender + " --environment " + path("sky.exr") +
                      " --out " + path("render"));
  ASSERT_EQ(render.code, 0) << render.err;

  // The floor sees the upper hemisphere only: E = pi kSky, radiance albedo kSky. In the render
  // the probes' L2 irradiance of a two-hemisphere step is exact too.
  const glm::dvec3 expected_floor = glm::dvec3(kAlbedo * kSky);
  for (const char* file : {"ref/reference.exr", "render/frame_0000.exr"}) {
    const Image im = image(file);
    const glm::dvec3 floor = mean(im, 0, 32, kFloorRow, 32);
    const glm::dvec3 sky = mean(im, 0, 32, 0, kSkyRows);
    std::printf("%s: floor (%.4f, %.4f, %.4f) sky (%.4f, %.4f, %.4f)\n", file, floor.x, floor.y,
                floor.z, sky.x, sky.y, sky.z);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(floor[c], expected_floor[c], 0.02 * expected_floor[c]) << file << " channel " << c;
      EXPECT_NEAR(sky[c], kSky[c], 1e-3) << file << " channel " << c << ": the background";
    }
  }
}

// The upper hemisphere is colour A where x < 0 and B where x > 0 (the file's u < 0.5 and
// u > 0.5): looking along -Z, A is on the left and B on the right. Turned 180 degrees they swap;
// turned 90 degrees (+Z -> +X -> -Z) the file's +X half fills the view: all B. Both renderers'
// backgrounds, the reference from a Radiance .hdr twin of the map.
TEST_F(EnvironmentCli, RotationTurnsTheMapAsDocumented) {
  const glm::vec3 a(0.9f, 0.1f, 0.1f);
  const glm::vec3 b(0.1f, 0.2f, 0.9f);
  const Image map = equirect(32, [&](int x, int y) {
    return y < 16 ? (x < 32 ? a : b) : glm::vec3(0.1f);
  });
  ddish::metrics::write_exr(dir_ / "halves.exr", map);
  write_hdr(dir_ / "halves.hdr", map);
  struct Case {
    const char* rotation;
    glm::vec3 left, right;
  };
  for (const Case& c : {Case{"0", a, b}, Case{"180", b, a}, Case{"90", b, b}}) {
    const std::string env = " --environment-rotation " + std::string(c.rotation) + " --environment ";
    Result ref = run("reference " + kPlane + kSize + " --spp 4" + env + path("halves.hdr") +
                     " --out " + path(std::string("ref") + c.rotation));
    ASSERT_EQ(ref.code, 0) << ref.err;
    Result render = run("render " + kPlane + kSize + kRender + env + path("halves.exr") +
                        " --out " + path(std::string("render") + c.rotation));
    ASSERT_EQ(render.code, 0) << render.err;
    for (const std::string& file : {std::string("ref") + c.rotation + "/reference.exr",
                                   std::string("render") + c.rotation + "/frame_0000.exr"}) {
      const Image im = image(file);
      // Columns 0..13 and 18..31: more than 2 degrees left or right of -Z. Radiance RGBE
      // (.hdr) keeps about 1 % of each value.
      const glm::dvec3 left = mean(im, 0, 14, 0, kSkyRows);
      const glm::dvec3 right = mean(im, 18, 32, 0, kSkyRows);
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(left[k], c.left[k], 0.01) << file << " channel " << k;
        EXPECT_NEAR(right[k], c.right[k], 0.01) << file << " channel " << k;
      }
    }
  }
}

TEST_F(EnvironmentCli, IntensityScalesTheLightAndProbesTakeTheMap) {
  ddish::metrics::write_exr(dir_ / "grey.exr", equirect(8, [](int, int) { return glm::vec3(1.0f); }));
  Result ref = run("reference " + kPlane + kSize + " --spp 16 --environment " + path("grey.exr") +
                   " --environment-intensity 3 --out " + path("ref"));
  ASSERT_EQ(ref.code, 0) << ref.err;
  const Image im = image("ref/reference.exr");
  EXPECT_NEAR(mean(im, 0, 32, 0, kSkyRows).x, 3.0, 1e-3);
  EXPECT_NEAR(mean(im, 0, 32, kFloorRow, 32).x, 3.0 * kAlbedo, 0.02 * 3.0 * kAlbedo);
  Result probes = run("probes " + kPlane + " --grid 2,2,2 --environment " + path("grey.exr") +
                      " --out " + path("volume"));
  ASSERT_EQ(probes.code, 0) << probes.err;
  EXPECT_NE(probes.out.find("environment map"), std::string::npos) << probes.out;
}

TEST_F(EnvironmentCli, BadMapsAreOneClearErrorLine) {
  ddish::metrics::write_exr(dir_ / "square.exr", Image(16, 16, glm::vec3(1.0f)));
  std::ofstream(dir_ / "garbage.exr") << "not an image";
  ddish::metrics::write_exr(dir_ / "ok.exr", Image(16, 8, glm::vec3(1.0f)));
  struct Case {
    std::string args;
    std::string message;
  };
  const Case cases[] = {
      {"reference " + kPlane + " --environment " + path("missing.exr"), "no such file"},
      {"render " + kPlane + " --environment " + path("garbage.exr"), "cannot read"},
      {"probes " + kPlane + " --environment " + path("square.exr"), "twice as wide as it is high"},
      {"reference " + kPlane + " --environment " + path("ok.png"), "an .exr or .hdr file"},
      {"render " + kPlane + " --sky 1,1,1 --environment " + path("ok.exr"), "excludes"},
      {"reference " + kPlane + " --environment " + path("ok.exr") + " --environment-intensity -1",
       "--environment-intensity"},
  };
  int k = 0;
  for (const Case& c : cases) {
    const Result r = run(c.args + " --out " + path("out" + std::to_string(k++)));
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    EXPECT_EQ(lines(r.err), 1) << c.args << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("ddish: error: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
  }
}

}  // namespace

// The sidecar's environment.map (with rotation and intensity) lights a scene as the same map on
// the command line does: the same images, bit for bit, from render and reference. --sky and
// --environment on the command line win over it; `info` names it; a malformed one is one line.
TEST_F(EnvironmentCli, SidecarMapLightsAsTheCommandLineMapDoes) {
  const fs::path src = fs::path(DDISH_SOURCE_DIR) / "scenes";
  fs::create_directories(dir_ / "scene" / "maps");
  fs::copy_file(src / "environment_plane.gltf", dir_ / "scene" / "environment_plane.gltf");
  fs::copy_file(src / "environment_plane.bin", dir_ / "scene" / "environment_plane.bin");
  const glm::vec3 a(0.9f, 0.1f, 0.1f), b(0.1f, 0.2f, 0.9f);
  ddish::metrics::write_exr(dir_ / "scene" / "maps" / "halves.exr", equirect(32, [&](int x, int y) {
                              return y < 16 ? (x < 32 ? a : b) : glm::vec3(0.1f);
                            }));
  const auto sidecar = [&](const std::string& text) {
    std::ofstream(dir_ / "scene" / "environment_plane.ddish.json") << text;
  };
  sidecar(R"({"environment": {"map": "maps/halves.exr", "rotation": 90, "intensity": 1.5}})");
  const std::string copy = quote((dir_ / "scene" / "environment_plane.gltf").string());
  const std::string flags =
      " --environment " + path("scene/maps/halves.exr") + " --environment-rotation 90 --environment-intensity 1.5";

  // No warm-up: a warm-up cut short by its time bound (a loaded CI machine) differs between runs.
  Result side = run("render " + copy + kSize + kRender + " --warmup-ms 0 --out " + path("side"));
  ASSERT_EQ(side.code, 0) << side.err;
  EXPECT_NE(side.err.find("(64x32, rotation 90 deg, intensity 1.5): sidecar"), std::string::npos) << side.err;
  Result cli = run("render " + kPlane + kSize + kRender + flags + " --warmup-ms 0 --out " + path("cli"));
  ASSERT_EQ(cli.code, 0) << cli.err;
  Result side_ref = run("reference " + copy + kSize + " --spp 4 --out " + path("side_ref"));
  ASSERT_EQ(side_ref.code, 0) << side_ref.err;
  Result cli_ref = run("reference " + kPlane + kSize + " --spp 4" + flags + " --out " + path("cli_ref"));
  ASSERT_EQ(cli_ref.code, 0) << cli_ref.err;
  for (const auto& [x, y] : {std::pair<const char*, const char*>{"side/frame_0000.exr", "cli/frame_0000.exr"},
                             {"side_ref/reference.exr", "cli_ref/reference.exr"}}) {
    const Image p = image(x), q = image(y);
    ASSERT_EQ(p.pixels().size(), q.pixels().size());
    EXPECT_TRUE(p.pixels() == q.pixels()) << x << " differs from " << y;
  }
  // Turned 90 degrees the view sees the map's +X half: B, brighter by the intensity.
  const glm::dvec3 sky = mean(image("side/frame_0000.exr"), 0, 32, 0, kSkyRows);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sky[c], 1.5 * b[c], 2e-3) << c;

  Result sky_wins = run("render " + copy + kSize + kRender + " --sky 0.5,0.5,0.5 --out " + path("sky"));
  ASSERT_EQ(sky_wins.code, 0) << sky_wins.err;
  EXPECT_NE(sky_wins.err.find("environment (0.5, 0.5, 0.5) radiance: --sky"), std::string::npos) << sky_wins.err;
  Result info = run("info " + copy);
  ASSERT_EQ(info.code, 0) << info.err;
  EXPECT_NE(info.out.find("maps/halves.exr (rotation 90 deg, intensity 1.5): sidecar"), std::string::npos)
      << info.out;

  const std::string file = (dir_ / "scene" / "environment_plane.ddish.json").string();
  for (const auto& [text, line] : std::vector<std::pair<std::string, std::string>>{
           {R"({"environment": {"map": "maps/none.exr"}})",
            "environment.map: cannot read " + (dir_ / "scene" / "maps" / "none.exr").string() + ": no such file"},
           {R"({"environment": {"map": "maps/halves.png"}})",
            "environment.map must be an .exr or .hdr file, got 'maps/halves.png'"},
           {R"({"environment": {"map": "maps/halves.exr", "radiance": [1, 1, 1]}})",
            "environment has both a radiance and a map: give one"},
           {R"({"environment": {"map": "maps/halves.exr", "intensity": -1}})",
            "environment.intensity must not be negative"},
           {R"({"environment": {"rotation": 10}})",
            "environment.rotation and environment.intensity need an environment.map"}}) {
    sidecar(text);
    Result r = run("info " + copy);
    EXPECT_EQ(r.code, 2) << text;
    EXPECT_EQ(r.err, "ddish: error: " + file + ": " + line + "\n") << text;
  }
}
