// `--probe-placement centres|fit` on the command line: the fitted grid is the centred one moved
// by the offset it reports, written into the volume file's summary, and an unknown value is one
// error line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.h"

namespace {

class ProbePlacementCli : public cli::TempDirTest {
 protected:
  ProbePlacementCli() : TempDirTest("ddish_placement_") {}

  nlohmann::json summary(const std::string& name) const {
    return nlohmann::json::parse(cli::slurp(dir_ / (name + ".json")));
  }
};

TEST_F(ProbePlacementCli, TheFittedGridIsTheCentredOneMovedByTheReportedOffset) {
  const std::string common = "probes " + cli::cornell() + " --grid 4,4,4 --probe-samples 16 --out ";
  const cli::Result centres = run(common + path("c.ddpv"));
  ASSERT_EQ(centres.code, 0) << centres.err;
  const cli::Result fit = run(common + path("f.ddpv") + " --probe-placement fit");
  ASSERT_EQ(fit.code, 0) << fit.err;
  EXPECT_NE(fit.err.find("probe placement: fit over "), std::string::npos) << fit.err;
  const auto at = fit.out.find("cells by --probe-placement fit");
  ASSERT_NE(at, std::string::npos) << fit.out;
  const auto moved = fit.out.rfind("moved (", at);
  ASSERT_NE(moved, std::string::npos) << fit.out;
  float o[3] = {0.0f, 0.0f, 0.0f};
  ASSERT_EQ(std::sscanf(fit.out.c_str() + moved, "moved (%f, %f, %f)", &o[0], &o[1], &o[2]), 3) << fit.out;
  const nlohmann::json c = summary("c.ddpv"), f = summary("f.ddpv");
  for (int a = 0; a < 3; ++a) {
    // Each offset is one of the candidates: 0 or a quarter cell either way.
    EXPECT_TRUE(o[a] == 0.0f || o[a] == 0.25f || o[a] == -0.25f) << o[a];
    const double spacing = c["spacing"][a].get<double>();
    EXPECT_NEAR(f["spacing"][a].get<double>(), spacing, 1e-5);
    EXPECT_NEAR(f["bounds"]["min"][a].get<double>(), c["bounds"]["min"][a].get<double>() + o[a] * spacing, 1e-4);
    EXPECT_NEAR(f["bounds"]["max"][a].get<double>(), c["bounds"]["max"][a].get<double>() + o[a] * spacing, 1e-4);
  }
}

TEST_F(ProbePlacementCli, AnUnknownPlacementIsOneErrorLine) {
  const cli::Result r = run("probes " + cli::cornell() + " --grid 2,2,2 --probe-placement middle");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("--probe-placement"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace
