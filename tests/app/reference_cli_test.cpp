// `ddish reference` end to end on a tiny Cornell box: the files it writes, the convergence CSV,
// and one line with exit code 2 for bad options. Image content is tested in
// tests/trace/reference_test.cpp; here it is the command line.
#include <algorithm>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"

namespace {

namespace fs = std::filesystem;

using cli::cornell;
using cli::quote;
using cli::Result;
using cli::slurp;

class ReferenceCli : public cli::TempDirTest {
 protected:
  ReferenceCli() : TempDirTest("ddish_reference_cli_") {}

  // `ddish reference ARGS`.
  Result run(const std::string& args) const { return TempDirTest::run("reference " + args); }
};

TEST_F(ReferenceCli, WritesImagesMetadataAndConvergence) {
  const fs::path out = dir_ / "out";
  const fs::path csv = dir_ / "curve.csv";
  Result r = run(cornell() + " --width 12 --height 8 --spp 16 --seed 3 --out " +
                 quote(out.string()) + " --convergence " + quote(csv.string()));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("16 spp"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Mrays/s"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(out / "reference.exr"));
  EXPECT_TRUE(fs::exists(out / "reference.png"));

  nlohmann::json meta = nlohmann::json::parse(slurp(out / "reference.json"));
  EXPECT_EQ(meta["width"], 12);
  EXPECT_EQ(meta["height"], 8);
  EXPECT_EQ(meta["spp"], 16);
  EXPECT_EQ(meta["seed"], 3);
  EXPECT_EQ(meta["nonfinite_samples"], 0);
  EXPECT_GT(meta["rays"].get<double>(), 12 * 8 * 16);

  // Points at 1 and 4 spp (16 is the final image itself), six columns each.
  std::string text = slurp(csv);
  EXPECT_EQ(text.rfind("spp,seconds,rmse,relmse,psnr,ssim\n1,", 0), 0u) << text;
  EXPECT_NE(text.find("\n4,"), std::string::npos) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 3) << text;
  EXPECT_EQ(std::count(text.begin(), text.end(), ','), 15) << text;
}

TEST_F(ReferenceCli, BadOptionsExitTwoWithOneLine) {
  for (const std::string& args :
       {cornell() + " --spp 0 --out " + quote(dir_.string()),
        cornell() + " --camera 1,2,3 --out " + quote(dir_.string()),
        cornell() + " --camera NoSuchCamera --out " + quote(dir_.string()),
        cornell() + " --time-limit -1 --out " + quote(dir_.string()), cornell()}) {
    Result r = run(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_EQ(r.err.rfind("ddish: error: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

}  // namespace
