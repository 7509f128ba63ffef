// `ddish compare` end to end: small images written here as binary PPM (8-bit, so display
// values, sRGB-encoded) and PFM (float, so linear values), figures checked against the
// formulas worked out in the test, and the exit code and one-line message for bad input.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"

namespace {

namespace fs = std::filesystem;

using cli::quote;
using cli::Result;

class CompareCli : public cli::TempDirTest {
 protected:
  CompareCli() : TempDirTest("ddish_compare_cli_") {}

  // `ddish compare ARGS`.
  Result run(const std::string& args) const { return TempDirTest::run("compare " + args); }

  // A w x h grey PPM whose every channel byte is `value` (display value value / 255).
  std::string ppm(const std::string& name, int w, int h, std::uint8_t value) const {
    fs::path p = dir_ / name;
    std::ofstream f(p, std::ios::binary);
    f << "P6\n" << w << ' ' << h << "\n255\n";
    std::string bytes(static_cast<std::size_t>(w * h * 3), static_cast<char>(value));
    f << bytes;
    return quote(p.string());
  }

  // A w x h linear PFM of constant RGB (little-endian: negative scale).
  std::string pfm(const fs::path& p, int w, int h, float r, float g, float b) const {
    std::ofstream f(p, std::ios::binary);
    f << "PF\n" << w << ' ' << h << "\n-1.0\n";
    for (int i = 0; i < w * h; ++i)
      for (float v : {r, g, b}) f.write(reinterpret_cast<const char*>(&v), sizeof v);
    return quote(p.string());
  }
};

double srgb_decode(double v) {
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

// The value printed on the line starting with `key` ("psnr    12.3 dB").
std::string figure(const std::string& out, const std::string& key) {
  std::istringstream in(out);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::string k, v;
    words >> k >> v;
    if (k == key) return v;
  }
  return "";
}

TEST_F(CompareCli, FiguresOfTwoGreyImages) {
  // Display values a = 64/255 and b = 192/255 everywhere (grey, so luminance = the value).
  const std::string a = ppm("a.ppm", 16, 16, 64);
  const std::string b = ppm("b.ppm", 16, 16, 192);
  Result r = run(a + " " + b);
  ASSERT_EQ(r.code, 0) << r.err;
  const double da = 64.0 / 255.0, db = 192.0 / 255.0;
  // PSNR = 10 log10(1 / (da - db)^2).
  const double psnr = -10.0 * std::log10((da - db) * (da - db));
  // Constant images: SSIM = (2 da db + C1) / (da^2 + db^2 + C1).
  const double c1 = 1e-4;
  const double ssim = (2 * da * db + c1) / (da * da + db * db + c1);
  // Linear: RMSE = |la - lb|, relMSE = (la - lb)^2 / (lb^2 + 0.01) with b the reference.
  const double la = srgb_decode(da), lb = srgb_decode(db);
  const double rmse = std::abs(la - lb);
  const double relmse = (la - lb) * (la - lb) / (lb * lb + 0.01);
  EXPECT_NEAR(std::stod(figure(r.out, "psnr")), psnr, 1e-4 * psnr);
  EXPECT_NEAR(std::stod(figure(r.out, "ssim")), ssim, 1e-5);
  EXPECT_NEAR(std::stod(figure(r.out, "rmse")), rmse, 1e-5 * rmse);
  EXPECT_NEAR(std::stod(figure(r.out, "relmse")), relmse, 1e-5 * relmse);

  Result j = run(a + " " + b + " --json");
  ASSERT_EQ(j.code, 0) << j.err;
  nlohmann::json doc = nlohmann::json::parse(j.out);
  EXPECT_NEAR(doc["psnr"].get<double>(), psnr, 1e-6 * psnr);
  EXPECT_NEAR(doc["ssim"].get<double>(), ssim, 1e-6);
  EXPECT_NEAR(doc["rmse"].get<double>(), rmse, 1e-5 * rmse);
  EXPECT_NEAR(doc["relmse"].get<double>(), relmse, 1e-5 * relmse);
}

TEST_F(CompareCli, IdenticalImagesHaveInfinitePsnr) {
  const std::string a = ppm("a.ppm", 12, 12, 100);
  Result r = run(a + " " + a);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(figure(r.out, "psnr"), "inf");
  EXPECT_EQ(figure(r.out, "ssim"), "1");
  EXPECT_EQ(figure(r.out, "rmse"), "0");
  Result j = run(a + " " + a + " --json");
  EXPECT_EQ(nlohmann::json::parse(j.out)["psnr"], "inf");
}

TEST_F(CompareCli, LinearFloatImages) {
  // Linear 2 and 1 both display as 1 (PSNR inf), but differ by 1 in linear terms.
  const std::string a = pfm(dir_ / "a.pfm", 4, 4, 2.0f, 2.0f, 2.0f);
  const std::string b = pfm(dir_ / "b.pfm", 4, 4, 1.0f, 1.0f, 1.0f);
  Result r = run(a + " " + b);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(figure(r.out, "psnr"), "inf");
  EXPECT_EQ(figure(r.out, "rmse"), "1");
  EXPECT_NEAR(std::stod(figure(r.out, "relmse")), 1.0 / 1.01, 1e-6);
}

TEST_F(CompareCli, DifferentSizesExitTwoWithOneLine) {
  Result r = run(ppm("a.ppm", 8, 8, 10) + " " + ppm("b.ppm", 8, 9, 10));
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(r.out.empty());
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;  // exactly one line
  EXPECT_NE(r.err.find("8x8"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("8x9"), std::string::npos) << r.err;
}

TEST_F(CompareCli, MissingFileExitsTwo) {
  Result r = run(ppm("a.ppm", 4, 4, 10) + " " + quote((dir_ / "nope.png").string()));
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST_F(CompareCli, DirectoriesPerView) {
  fs::create_directories(dir_ / "out");
  fs::create_directories(dir_ / "ref");
  pfm(dir_ / "out" / "view_0.pfm", 4, 4, 0.5f, 0.5f, 0.5f);
  pfm(dir_ / "ref" / "view_0.pfm", 4, 4, 0.5f, 0.5f, 0.5f);
  pfm(dir_ / "out" / "view_1.pfm", 4, 4, 0.75f, 0.75f, 0.75f);
  pfm(dir_ / "ref" / "view_1.pfm", 4, 4, 0.5f, 0.5f, 0.5f);
  const std::string dirs = quote((dir_ / "out").string()) + " " + quote((dir_ / "ref").string());
  Result r = run(dirs + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json doc = nlohmann::json::parse(r.out);
  ASSERT_EQ(doc["views"].size(), 2u);
  EXPECT_EQ(doc["views"][0]["name"], "view_0.pfm");
  EXPECT_EQ(doc["views"][0]["psnr"], "inf");
  EXPECT_NEAR(doc["views"][1]["rmse"].get<double>(), 0.25, 1e-7);
  EXPECT_NEAR(doc["mean"]["rmse"].get<double>(), 0.125, 1e-7);

  Result t = run(dirs);
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.out.find("view_1.pfm"), std::string::npos);
  EXPECT_NE(t.out.find("mean"), std::string::npos);
}

TEST_F(CompareCli, QuiltPerView) {
  // An 8x2 PPM quilt named as 2x1 views: both views equal, so every PSNR is inf.
  const std::string q = ppm("render_qs2x1a2.ppm", 8, 2, 50);
  Result r = run(q + " " + q + " --views 2 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  nlohmann::json doc = nlohmann::json::parse(r.out);
  ASSERT_EQ(doc["views"].size(), 2u);
  EXPECT_EQ(doc["views"][1]["name"], "view 1");
  Result bad = run(ppm("plain.ppm", 8, 2, 50) + " " + q + " --views 2");
  EXPECT_EQ(bad.code, 2);
}

}  // namespace
