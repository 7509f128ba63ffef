// A Draco-compressed box renders as its plain twin (scenes/draco_box_draco.gltf and
// scenes/draco_box.gltf, tests/scene/draco_test.cpp): the same framing camera, the same image in
// the rasterizer and the path tracer, to within what 20-bit quantization of the vertices moves.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "cli_runner.h"
#include "metrics/image.h"
#include "metrics/image_io.h"

namespace {

using cli::quote;
using cli::Result;

std::string bundled(const std::string& name) {
  return quote(std::string(DDISH_SOURCE_DIR) + "/scenes/" + name);
}

class DracoCli : public cli::TempDirTest {
 protected:
  DracoCli() : TempDirTest("ddish_draco_cli_") {}
};

TEST_F(DracoCli, RendersAsItsPlainTwin) {
  const std::string size = " --width 32 --height 32";
  for (const char* stem : {"draco_box", "draco_box_draco"}) {
    const std::string scene = bundled(std::string(stem) + ".gltf");
    Result render = run("render " + scene + size + " --msaa 1 --tonemap linear --grid 2,2,2 --out " +
                        path(std::string("render_") + stem));
    ASSERT_EQ(render.code, 0) << render.err;
    Result ref = run("reference " + scene + size + " --spp 4 --out " + path(std::string("ref_") + stem));
    ASSERT_EQ(ref.code, 0) << ref.err;
  }
  for (const std::string& file : {std::string("render_%s/frame_0000.exr"), std::string("ref_%s/reference.exr")}) {
    auto name = [&](const char* stem) {
      std::string f = file;
      return f.replace(f.find("%s"), 2, stem);
    };
    const auto a = ddish::metrics::read_image(dir_ / name("draco_box"));
    const auto b = ddish::metrics::read_image(dir_ / name("draco_box_draco"));
    ASSERT_EQ(a.width(), b.width());
    double worst = 0.0;
    double sum = 0.0;
    for (std::size_t i = 0; i < a.pixels().size(); ++i)
      for (int c = 0; c < 3; ++c) {
        const double d = std::abs(double(a.pixels()[i][c]) - double(b.pixels()[i][c]));
        worst = std::max(worst, d);
        sum += d;
      }
    const double mean = sum / double(3 * a.pixels().size());
    std::printf("%s: mean |difference| %.2e, largest %.2e\n", file.c_str(), mean, worst);
    EXPECT_LT(mean, 1e-3) << file;
    EXPECT_LT(worst, 0.05) << file;
  }
}

}  // namespace
