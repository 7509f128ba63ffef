// `ddish render --schedule / --budget-ms / --max-age / --blend`, read back from the --timings
// JSON: uniform traces every active probe every frame; visibility with a tiny budget traces fewer
// probes per frame than uniform yet reaches every active probe within --max-age frames and
// uploads only what it traced; bad values are one line with exit code 2; and the run log lists
// what the Cornell box leaves out (no punctual lights: no shadow maps) while the renderer
// records zero shadow passes.
#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "display_cli.h"

namespace {

using namespace display_cli;

// A 4 × 4 × 4 grid, few paths, tiny single view: the tests are about counts, not images, of
// the per-frame schedule from cold probes (no warm-up before frame 0).
const std::string kTiny =
    " --grid 4,4,4 --probe-samples 8 --bounces 1 --msaa 1 --width 16 --height 16 --warmup-ms 0";

class RenderScheduleCli : public Cli {
 protected:
  // Runs `render cornell ARGS` with --timings and returns the frames of its JSON.
  nlohmann::json frames(const std::string& args, const std::string& name) {
    const Result r = run("render " + cornell() + kTiny + args + " --out " + path("out") +
                         " --timings " + path(name));
    EXPECT_EQ(r.code, 0) << r.err;
    last_err_ = r.err;
    if (r.code != 0) return nlohmann::json::array();
    return nlohmann::json::parse(slurp(dir_ / name))["frames"];
  }
  std::string last_err_;
};

TEST_F(RenderScheduleCli, UniformTracesEveryActiveProbeEveryFrame) {
  const nlohmann::json fs_ = frames(" --schedule uniform --frames 4", "uniform.json");
  ASSERT_EQ(fs_.size(), 4u);
  for (const auto& f : fs_) {
    const auto& p = f["scheduler"]["probes"];
    EXPECT_EQ(f["probe_updates"], 1);
    EXPECT_EQ(f["scheduler"]["mode"], "uniform");
    EXPECT_TRUE(f["scheduler"]["budget_ms"].is_null());
    // active: before this frame's update (the first one classifies, and may deactivate some).
    EXPECT_EQ(p["traced"], p["active"]);
    EXPECT_EQ(p["skipped"], 0);
    EXPECT_EQ(p["samples_per_probe"], 8);
    EXPECT_EQ(f["probes_traced"], p["traced"]);
    EXPECT_EQ(f["probes_never_updated"], 0);
    EXPECT_EQ(f["oldest_probe_age"], 0);
    EXPECT_EQ(f["probes_active"].get<int>() + f["probes_inactive"].get<int>(), 64);
  }
  EXPECT_EQ(fs_[0]["scheduler"]["probes"]["active"], 64);  // all active until classified
  EXPECT_NE(last_err_.find("render: schedule uniform, blend per-update"), std::string::npos)
      << last_err_;
}

TEST_F(RenderScheduleCli, TinyBudgetTracesFewerButEveryProbeWithinMaxAge) {
  const int max_age = 4;
  const int n = 8;
  const nlohmann::json uni =
      frames(" --schedule uniform --frames " + std::to_string(n), "uniform.json");
  const nlohmann::json vis =
      frames(" --schedule visibility --budget-ms 0.001 --max-age " + std::to_string(max_age) +
                 " --frames " + std::to_string(n),
             "visibility.json");
  ASSERT_EQ(uni.size(), std::size_t(n));
  ASSERT_EQ(vis.size(), std::size_t(n));
  EXPECT_NE(last_err_.find("render: schedule visibility, blend per-sample, max age 4 frames, "
                           "budget 0.001 ms per frame"),
            std::string::npos)
      << last_err_;
  EXPECT_NE(last_err_.find(" of budget 0.001 ms (over)"), std::string::npos) << last_err_;
  for (int k = 0; k < n; ++k) {
    const auto& f = vis[k];
    const auto& s = f["scheduler"];
    EXPECT_EQ(f["probe_updates"], 1) << k;
    EXPECT_EQ(s["budget_ms"], 0.001) << k;
    EXPECT_EQ(s["within_budget"], false) << k;
    // Only the max-age promise is kept: a quarter of the active probes (ceil), plus overdue.
    EXPECT_LT(s["probes"]["traced"].get<int>(), uni[k]["scheduler"]["probes"]["traced"].get<int>())
        << k;
    EXPECT_GT(s["probes"]["traced"].get<int>(), 0) << k;
    EXPECT_EQ(s["probes"]["traced"].get<int>() + s["probes"]["skipped"].get<int>(),
              s["probes"]["active"].get<int>())
        << k;
    EXPECT_TRUE(s["over_allowance"].get<bool>()) << k;
    EXPECT_GT(s["rays"].get<std::uint64_t>(), 0u) << k;
    EXPECT_LE(f["oldest_probe_age"].get<int>(), max_age) << k;
    if (k >= max_age - 1) {
      EXPECT_EQ(f["probes_never_updated"], 0) << k;
    }
    // Only what this frame traced (or found inside geometry, which it traced too) is handed
    // to the renderer, which made the first, full upload itself.
    EXPECT_EQ(f["probes_changed"], s["probes"]["traced"]) << k;
  }
  EXPECT_GT(vis[0]["probes_never_updated"].get<int>(), 0);
}

TEST_F(RenderScheduleCli, BadScheduleOptionsAreOneLineExitTwo) {
  for (const std::string& args :
       std::vector<std::string>{" --schedule sometimes", " --budget-ms -1", " --budget-ms nan",
                                " --budget-ms soon", " --blend average", " --max-age 0"}) {
    const Result r = run("render " + cornell() + args + " --out " + path("out"));
    EXPECT_EQ(r.code, 2) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("ddish: error: ", 0), 0u) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  }
  EXPECT_FALSE(fs::exists(dir_ / "out" / "frame_0000.png"));
}

TEST_F(RenderScheduleCli, RunLogListsWhatIsLeftOutAndNoShadowPassRuns) {
  const nlohmann::json fs_ = frames(" --frames 2", "t.json");
  ASSERT_EQ(fs_.size(), 2u);
  for (const auto& f : fs_) EXPECT_EQ(f["raster_passes"]["shadow"], 0);
  EXPECT_NE(last_err_.find("render: left out\n"), std::string::npos) << last_err_;
  EXPECT_NE(last_err_.find("  shadow maps: the scene has no punctual lights\n"), std::string::npos)
      << last_err_;
  EXPECT_NE(last_err_.find(" of 64 probes inside geometry: never traced or uploaded"),
            std::string::npos)
      << last_err_;
  // The same items as `ddish info` prints under "left out", but for the probes with no surface
  // near them: info counts them on the default grid (8 x 8 x 8 from the sidecar), this run's
  // --grid 4,4,4 has none (every cell of so coarse a grid reaches a wall).
  const Result info = run("info " + cornell());
  ASSERT_EQ(info.code, 0) << info.err;
  std::istringstream lines(info.out.substr(info.out.find("left out\n") + 9));
  int items = 0, grid_items = 0;
  for (std::string line; std::getline(lines, line) && line.rfind("  ", 0) == 0;) {
    if (line.find(" of the grid's 512 probes (8 x 8 x 8): no surface") != std::string::npos) {
      ++grid_items;
      continue;
    }
    ++items;
    EXPECT_NE(last_err_.find(line + "\n"), std::string::npos) << line;
  }
  EXPECT_GE(items, 2);
  EXPECT_EQ(grid_items, 1);
  EXPECT_EQ(last_err_.find(" of the grid's "), std::string::npos) << last_err_;
}

}  // namespace

// --no-indirect draws no probes, so it must not trace them either: its frame time is the
// direct-light baseline of the results report.
TEST_F(RenderScheduleCli, NoIndirectNeitherTracesNorUploadsProbes) {
  const nlohmann::json fs_ = frames(" --no-indirect --frames 3", "direct.json");
  ASSERT_EQ(fs_.size(), 3u);
  for (const auto& f : fs_) {
    EXPECT_EQ(f["probe_updates"], 0);
    EXPECT_EQ(f["probe_rays"], 0);
    EXPECT_EQ(f["probes_traced"], 0);
    EXPECT_EQ(f["probes_uploaded"], 0);
  }
  EXPECT_NE(last_err_.find("probes are neither traced nor drawn"), std::string::npos) << last_err_;
}
