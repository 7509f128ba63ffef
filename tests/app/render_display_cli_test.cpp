// `ddish render --display`: the quilt's name and size follow the profile (and --views /
// --width / --height), a 48-view quilt renders with zero validation errors, the probe tracer runs
// exactly once per frame whatever the number of views (counted from the timings JSON), stereo
// writes a side-by-side pair, a calibration adds the lenticular panel image, and bad display
// options are one line with exit code 2.
#include <algorithm>
#include <string>
#include <vector>

#include "display_cli.h"
#include "metrics/image_io.h"

namespace {

using namespace display_cli;

// Small tiles and few probe paths: the tests are about files and counts, not image quality.
const std::string kFast = " --probe-samples 16 --msaa 1";

class RenderDisplayCli : public Cli {
 protected:
  // A Looking Glass calibration for a 60 × 80 panel (made-up numbers of the usual magnitudes).
  std::string calibration() const {
    const fs::path file = dir_ / "visual.json";
    std::ofstream(file) << R"({"pitch": {"value": 52.0}, "slope": {"value": -7.2},
      "center": {"value": 0.3}, "DPI": {"value": 324.0}, "screenW": {"value": 60.0},
      "screenH": {"value": 80.0}, "invView": {"value": 1.0}, "flipImageX": {"value": 0.0},
      "flipImageY": {"value": 0.0}, "flipSubp": {"value": 0.0}})";
    return quote(file.string());
  }
};

TEST_F(RenderDisplayCli, QuiltNameAndSizeFollowTheProfileWithTileOverride) {
  Result r = run("render " + cornell() + " --display looking-glass-portrait --width 42 --height 56"
                 " --out " + path("out") + kFast);
  ASSERT_EQ(r.code, 0) << r.err;
  const fs::path png = dir_ / "out" / "cornell_box_qs8x6a0.75.png";
  EXPECT_EQ(png_size(png), std::make_pair(336, 336));  // 8 × 42 by 6 × 56
  EXPECT_TRUE(fs::exists(dir_ / "out" / "cornell_box_qs8x6a0.75.exr"));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "view_00.png"));  // only with --per-view
}

TEST_F(RenderDisplayCli, FullSizePortraitQuiltIs3360Square) {
  Result r = run("render " + cornell() + " --display looking-glass-portrait --out " + path("out") +
                 kFast);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(png_size(dir_ / "out" / "cornell_box_qs8x6a0.75.png"), std::make_pair(3360, 3360));
}

TEST_F(RenderDisplayCli, FortyEightViewsWithoutValidationErrors) {
  if (run("devices --validation").code != 0) GTEST_SKIP() << "no Vulkan validation layer";
  Result r = run("render " + cornell() + " --display looking-glass-portrait --width 42 --height 56"
                 " --out " + path("out") + kFast,
                 "DDISH_VALIDATION=1");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("render: validation: 0 errors"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("48 views"), std::string::npos) << r.err;
}

TEST_F(RenderDisplayCli, ProbeTracerRunsOncePerFrameWhateverTheViews) {
  std::vector<std::uint64_t> rays;
  std::vector<std::uint32_t> traced;
  std::uint32_t left_out = 0;
  for (int views : {1, 2, 48}) {
    std::string timings = "t";
    timings += std::to_string(views);
    timings += ".json";
    Result r = run("render " + cornell() + " --display looking-glass-portrait --views " +
                   std::to_string(views) + " --width 12 --height 16 --frames 3 --out " +
                   path("out") + " --timings " + path(timings) + kFast + " --warmup-ms 0");
    ASSERT_EQ(r.code, 0) << r.err;
    // Classification's second phase leaves out the probes with no surface near them before the
    // first update; the run log says how many.
    const std::size_t at = r.err.find(" of the grid's 512 probes (8 x 8 x 8): no surface");
    ASSERT_NE(at, std::string::npos) << r.err;
    left_out = std::uint32_t(std::stoul(r.err.substr(r.err.rfind(' ', at - 1) + 1)));
    const nlohmann::json doc = nlohmann::json::parse(slurp(dir_ / timings));
    EXPECT_EQ(doc["display"]["views"], views);
    ASSERT_EQ(doc["frames"].size(), 3u);
    std::uint64_t total = 0;
    for (const auto& f : doc["frames"]) {
      EXPECT_EQ(f["probe_updates"], 1) << "views " << views;
      EXPECT_EQ(f["views"], views);
      traced.push_back(f["probes_traced"].get<std::uint32_t>());
      const double forward = f["stages_ms"]["forward_gpu"].get<double>();
      EXPECT_NEAR(f["per_view_ms"]["forward_gpu"].get<double>() * views, forward, 1e-9 + 1e-9 * forward);
      total += f["probe_rays"].get<std::uint64_t>();
    }
    rays.push_back(total);
  }
  // Same seed, same probe work: the views do not add a single probe or probe ray. The first
  // update traces every probe of the sidecar's 8 × 8 × 8 grid that is not left out (it
  // classifies them all); the Cornell box's closed room leaves a few out in its middle.
  ASSERT_EQ(traced.size(), 9u);
  EXPECT_GT(left_out, 0u);
  EXPECT_LT(left_out, 512u / 8u);
  EXPECT_EQ(traced[0], 512u - left_out);
  for (std::size_t i = 3; i < traced.size(); ++i) EXPECT_EQ(traced[i], traced[i % 3]) << i;
  EXPECT_GT(rays[0], 0u);
  EXPECT_EQ(rays[1], rays[0]);
  EXPECT_EQ(rays[2], rays[0]);
}

TEST_F(RenderDisplayCli, ViewsRecomputeTheQuiltLayout) {
  Result r = run("render " + cornell() + " --display looking-glass-portrait --views 8 --width 10"
                 " --height 12 --per-view --out " + path("out") + kFast);
  ASSERT_EQ(r.code, 0) << r.err;
  // 8 tiles of 10 × 12: 4 × 2 (no empty cell, nearest to square of those).
  EXPECT_EQ(png_size(dir_ / "out" / "cornell_box_qs4x2a0.75.png"), std::make_pair(40, 24));
  EXPECT_EQ(png_size(dir_ / "out" / "view_7.png"), std::make_pair(10, 12));
  EXPECT_TRUE(fs::exists(dir_ / "out" / "view_0.exr"));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "view_8.png"));
}

TEST_F(RenderDisplayCli, StereoWritesSideBySide) {
  Result r = run("render " + cornell() + " --display stereo --width 40 --height 30 --out " +
                 path("out") + kFast);
  ASSERT_EQ(r.code, 0) << r.err;
  // The aspect of stereo-hmd's eye angles: (tan 50° + tan 43°) / (tan 47° + tan 53°) = 0.885.
  EXPECT_EQ(png_size(dir_ / "out" / "cornell_box_sbs_qs2x1a0.88.png"), std::make_pair(80, 30));
  EXPECT_TRUE(fs::exists(dir_ / "out" / "cornell_box_sbs_qs2x1a0.88.exr"));
}

TEST_F(RenderDisplayCli, CalibrationWritesTheLenticularPanel) {
  Result r = run("render " + cornell() + " --display looking-glass-portrait --width 15 --height 20"
                 " --calibration " + calibration() + " --out " + path("out") + kFast);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(png_size(dir_ / "out" / "cornell_box_lenticular.png"), std::make_pair(60, 80));
}

// --formats writes only the formats named, quilt and views alike, and leaving one out changes
// nothing in the other: without the EXR no linear pixels are read back, and the PNG bytes are
// those of the run that wrote both (direct light only, so both runs draw the same image).
TEST_F(RenderDisplayCli, FormatsWriteOnlyTheFilesNamedAndTheSameBytes) {
  const std::string common = "render " + cornell() + " --display looking-glass-portrait --views 2 --width 12"
                             " --height 16 --per-view --no-indirect" + kFast;
  ASSERT_EQ(run(common + " --out " + path("both")).code, 0);
  Result png = run(common + " --formats png --out " + path("png"));
  ASSERT_EQ(png.code, 0) << png.err;
  Result exr = run(common + " --formats exr --out " + path("exr"));
  ASSERT_EQ(exr.code, 0) << exr.err;
  for (const std::string stem : {"cornell_box_qs2x1a0.75", "view_0", "view_1"}) {
    EXPECT_EQ(slurp(dir_ / "png" / (stem + ".png")), slurp(dir_ / "both" / (stem + ".png"))) << stem;
    EXPECT_FALSE(fs::exists(dir_ / "png" / (stem + ".exr"))) << stem;
    // The EXR header holds the time it was written: the pixels are compared.
    EXPECT_EQ(ddish::metrics::read_image(dir_ / "exr" / (stem + ".exr")).pixels(),
              ddish::metrics::read_image(dir_ / "both" / (stem + ".exr")).pixels()) << stem;
    EXPECT_FALSE(fs::exists(dir_ / "exr" / (stem + ".png"))) << stem;
  }
  double sum = 0.0;  // the linear pixels that were read back are the image, not zeros
  const ddish::metrics::Image view = ddish::metrics::read_image(dir_ / "both" / "view_1.exr");
  for (const auto& p : view.pixels()) sum += p.x + p.y + p.z;
  EXPECT_GT(sum, 0.0);

  Result bad = run("render " + cornell() + " --formats png,jpg --out " + path("bad"));
  EXPECT_EQ(bad.code, 2) << bad.err;
  EXPECT_EQ(bad.err, "ddish: error: --formats: jpg not in {png,exr} (see ddish --help)\n");
  EXPECT_FALSE(fs::exists(dir_ / "bad"));
}

TEST_F(RenderDisplayCli, BadDisplayOptionsAreOneLineExitTwo) {
  const std::string out = " --out " + path("out");
  Result bad = run("render " + cornell() + " --display no-such-display" + out);
  EXPECT_EQ(bad.code, 2);
  EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
  for (const char* name : {"looking-glass-portrait", "looking-glass-16", "stereo-hmd", "single"})
    EXPECT_NE(bad.err.find(name), std::string::npos) << bad.err;

  for (const std::string& args : std::vector<std::string>{
           " --display looking-glass-portrait --views 0", " --views 0", " --views 4",
        " --display stereo --views 3", " --display lightfield-32x720p --views 8",
        " --display looking-glass-portrait --views 5000",
        " --display looking-glass-portrait --focal-distance -1",
        " --display stereo --calibration " + calibration(),
        " --display looking-glass-portrait --calibration " +
            quote(std::string(DDISH_SOURCE_DIR) + "/README.md")}) {
    Result r = run("render " + cornell() + args + out);
    EXPECT_EQ(r.code, 2) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("ddish: error: ", 0), 0u) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  }
  EXPECT_FALSE(fs::exists(dir_ / "out" / "frame_0000.png"));
}

}  // namespace

namespace {

using namespace display_cli;

class DisplayListCli : public Cli {};

TEST_F(DisplayListCli, ListsEveryProfileWithItsPanelAndNeedsNoScene) {
  Result r = run("render --display list");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* line : {"looking-glass-portrait        48 views  quilt 8x6 of 3360x3360, tiles 420x560, panel 1536x2048",
                           "looking-glass-go              66 views  quilt 11x6 of 4092x4092, tiles 372x682, panel 1440x2560",
                           "looking-glass-65              72 views  quilt 8x9 of 8192x8190, tiles 1024x910, panel 7680x4320",
                           "stereo-hmd                     2 views  quilt 2x1 of 2880x1600, tiles 1440x1600\n"})
    EXPECT_NE(r.out.find(line), std::string::npos) << line << "\n" << r.out;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 11) << r.out;  // the 11 in displays/
}

}  // namespace
