// `ddish reference --display`: the same views as `ddish render --display`, written as a quilt of
// the same name plus per-view files, so `ddish compare --views N` gives a figure for every view.
#include <string>

#include "display_cli.h"

namespace {

using namespace display_cli;

class ReferenceDisplayCli : public Cli {};

// Four 24 × 32 views: the layout is 2 × 2 (no empty cell, and 48 × 64 is the squarest atlas),
// small enough for a 16-spp reference in about a second.
const std::string kFourViews = " --display looking-glass-portrait --views 4 --width 24 --height 32";

TEST_F(ReferenceDisplayCli, WritesQuiltAndViewsThatCompareViewByView) {
  Result ref = run("reference " + cornell() + kFourViews + " --spp 16 --out " + path("ref"));
  ASSERT_EQ(ref.code, 0) << ref.err;
  EXPECT_NE(ref.out.find("4 views of 24x32, 16 spp"), std::string::npos) << ref.out;
  const fs::path quilt = dir_ / "ref" / "cornell_box_qs2x2a0.75.exr";
  EXPECT_EQ(png_size(dir_ / "ref" / "cornell_box_qs2x2a0.75.png"), std::make_pair(48, 64));
  ASSERT_TRUE(fs::exists(quilt));
  for (int v = 0; v < 4; ++v) {
    EXPECT_EQ(png_size(dir_ / "ref" / ("view_" + std::to_string(v) + ".png")), std::make_pair(24, 32));
    EXPECT_TRUE(fs::exists(dir_ / "ref" / ("view_" + std::to_string(v) + ".exr")));
  }
  const nlohmann::json meta = nlohmann::json::parse(slurp(dir_ / "ref" / "reference.json"));
  EXPECT_EQ(meta["views"], 4);
  EXPECT_EQ(meta["display"], "looking-glass-portrait");
  ASSERT_EQ(meta["per_view"].size(), 4u);
  EXPECT_EQ(meta["per_view"][3]["spp"], 16);

  Result render = run("render " + cornell() + kFourViews + " --probe-samples 64 --per-view --out " +
                      path("render"));
  ASSERT_EQ(render.code, 0) << render.err;
  const fs::path rendered = dir_ / "render" / "cornell_box_qs2x2a0.75.exr";
  ASSERT_TRUE(fs::exists(rendered));

  Result cmp = run("compare " + quote(rendered.string()) + " " + quote(quilt.string()) +
                   " --views 4 --json");
  ASSERT_EQ(cmp.code, 0) << cmp.err;
  const nlohmann::json figures = nlohmann::json::parse(cmp.out);
  ASSERT_EQ(figures["views"].size(), 4u);
  EXPECT_EQ(figures["views"][0]["name"], "view 0");

  // The same cameras: every rendered view is nearer its own reference than the reference of the
  // farthest view of the rig (views 0 and 3 are 40° apart).
  auto psnr = [&](int view, int reference) {
    const std::string name = "view_" + std::to_string(view) + ".exr";
    const std::string ref_name = "view_" + std::to_string(reference) + ".exr";
    Result c = run("compare " + quote((dir_ / "render" / name).string()) + " " +
                   quote((dir_ / "ref" / ref_name).string()) + " --json");
    EXPECT_EQ(c.code, 0) << c.err;
    return nlohmann::json::parse(c.out)["psnr"].get<double>();
  };
  for (int v = 0; v < 4; ++v) {
    const int far = v < 2 ? 3 : 0;
    const double own = psnr(v, v);
    const double other = psnr(v, far);
    EXPECT_GT(own, other + 1.0) << "view " << v << " against reference " << v << " and " << far;
  }
}

TEST_F(ReferenceDisplayCli, ConvergenceIsForOneViewOnly) {
  Result r = run("reference " + cornell() + kFourViews + " --spp 1 --out " + path("ref") +
                 " --convergence " + path("c.csv"));
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err.rfind("ddish: error: --convergence", 0), 0u) << r.err;
}

}  // namespace
