// `--tracer auto|embree|vulkan`: auto never takes the Vulkan tracer on a CPU device (so the
// suite traces with Embree on lavapipe), vulkan traces the probes on lavapipe 25 under the
// validation layer (with distance moments and relocation; a textured, alpha-masked scene, an
// environment map and a skinned mesh that bends from frame to frame too; `render` hands the traced
// probes to the rasterizer on the GPU, or with --probe-readback through the CPU, with the same
// image), and on a device without ray tracing `--tracer vulkan` is one
// error line and exit 2.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "metrics/image.h"
#include "metrics/image_io.h"

namespace {

class TracerCli : public cli::TempDirTest {
 protected:
  TracerCli() : TempDirTest("ddish_tracer_") {}

  // Whether the default device has ray-tracing pipelines, as `ddish devices` says.
  bool ray_tracing() const {
    const cli::Result r = run("devices");
    const auto at = r.out.find("[default]");
    return at != std::string::npos && r.out.find("ray tracing            pipelines", at) != std::string::npos;
  }
};

TEST_F(TracerCli, AutoIsEmbreeOnACpuDevice) {
  const cli::Result r = run("probes " + cli::cornell() + " --grid 2,2,2 --probe-samples 16");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("tracer   embree (auto: "), std::string::npos) << r.out;
  const cli::Result info = run("info " + cli::cornell());
  ASSERT_EQ(info.code, 0) << info.err;
  EXPECT_NE(info.out.find("  probe tracer embree (auto: "), std::string::npos) << info.out;
}

TEST_F(TracerCli, VulkanTracesTheProbesWithValidationClean) {
  if (!ray_tracing()) GTEST_SKIP() << "the default Vulkan device has no ray-tracing pipelines";
  const cli::Result r = run("probes " + cli::cornell() + " --grid 3,3,3 --probe-samples 32 --updates 2 --tracer vulkan "
                            "--out " + path("v.ddprobes"),
                            "DDISH_VALIDATION=1");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("tracer   vulkan on "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("update 2/2: "), std::string::npos) << r.out;
  EXPECT_EQ(r.err.find("VUID"), std::string::npos) << r.err;  // the layer reports to stderr
  // It gathers --probe-visibility's distance moments (8 by default) into the file, as Embree does.
  std::ifstream summary(dir_ / "v.ddprobes.json");
  const std::string json((std::istreambuf_iterator<char>(summary)), std::istreambuf_iterator<char>());
  EXPECT_NE(json.find("\"moment_resolution\": 8"), std::string::npos) << json;
  const cli::Result moved = run("probes " + cli::cornell() + " --grid 4,4,4 --probe-samples 32 --tracer vulkan "
                                "--probe-relocation", "DDISH_VALIDATION=1");
  ASSERT_EQ(moved.code, 0) << moved.err;
  EXPECT_EQ(moved.err.find("VUID"), std::string::npos) << moved.err;
  // The renderer shares the tracer's device: the traced probes reach it on the GPU (converted
  // there, none uploaded), and the image is the one of the read-back path, byte for byte.
  const std::string frames = "render " + cli::cornell() + " --width 32 --height 32 --frames 2 --probe-samples 16 "
                             "--warmup-ms 0 --grid 3,3,3 --tracer vulkan ";
  const cli::Result render = run(frames + "--timings " + path("gpu.json") + " --out " + path("out"), "DDISH_VALIDATION=1");
  ASSERT_EQ(render.code, 0) << render.err;
  EXPECT_NE(render.err.find("render: probe tracer vulkan on "), std::string::npos) << render.err;
  EXPECT_NE(render.err.find("render: traced probes stay on the GPU"), std::string::npos) << render.err;
  EXPECT_EQ(render.err.find("VUID"), std::string::npos) << render.err;
  const cli::Result readback = run(frames + "--probe-readback --timings " + path("cpu.json") + " --out " + path("cpu"));
  ASSERT_EQ(readback.code, 0) << readback.err;
  EXPECT_EQ(readback.err.find("traced probes stay on the GPU"), std::string::npos) << readback.err;
  const auto frame_counts = [&](const std::string& file) {
    std::ifstream in(dir_ / file);
    const nlohmann::json j = nlohmann::json::parse(in);
    std::vector<std::pair<int, int>> counts;
    for (const auto& f : j["frames"]) counts.emplace_back(f["probes_uploaded"].get<int>(), f["probes_imported"].get<int>());
    return counts;
  };
  const auto on_gpu = frame_counts("gpu.json"), through_cpu = frame_counts("cpu.json");
  ASSERT_EQ(on_gpu.size(), 2u);
  ASSERT_EQ(through_cpu.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(on_gpu[k].first, 0) << "frame " << k;  // no probe uploaded from the CPU
    EXPECT_GT(on_gpu[k].second, 0) << "frame " << k;
    EXPECT_EQ(through_cpu[k], std::make_pair(on_gpu[k].second, 0)) << "frame " << k;
  }
  const auto bytes = [&](const std::string& file) {
    std::ifstream in(dir_ / file, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  EXPECT_FALSE(bytes("out/frame_0001.png").empty());
  EXPECT_EQ(bytes("out/frame_0001.png"), bytes("cpu/frame_0001.png"));
  const cli::Result textured = run("probes " + cli::quote(std::string(DDISH_SOURCE_DIR) + "/scenes/blend_panels_lit.gltf") +
                                   " --grid 2,2,2 --probe-samples 16 --tracer vulkan", "DDISH_VALIDATION=1");
  ASSERT_EQ(textured.code, 0) << textured.err;
  EXPECT_EQ(textured.err.find("VUID"), std::string::npos) << textured.err;
  ddish::metrics::write_exr(dir_ / "sky.exr", ddish::metrics::Image(16, 8, glm::vec3(0.5f)));
  const cli::Result map = run("probes " + cli::cornell() + " --grid 2,2,2 --probe-samples 16 --environment " +
                              path("sky.exr") + " --tracer vulkan", "DDISH_VALIDATION=1");
  ASSERT_EQ(map.code, 0) << map.err;
  EXPECT_NE(map.out.find("tracer   vulkan on "), std::string::npos) << map.out;
  EXPECT_EQ(map.err.find("VUID"), std::string::npos) << map.err;
  // The bar bends between the frames (0.5 s apart): its vertices and bottom level follow.
  const cli::Result skin = run("render " + cli::quote(std::string(DDISH_SOURCE_DIR) + "/scenes/skinned_bar.gltf") +
                                   " --width 32 --height 32 --frames 2 --fps 2 --probe-samples 16 --warmup-ms 0 "
                                   "--grid 2,2,2 --tracer vulkan --out " + path("skin"),
                               "DDISH_VALIDATION=1");
  ASSERT_EQ(skin.code, 0) << skin.err;
  EXPECT_NE(skin.err.find("render: probe tracer vulkan on "), std::string::npos) << skin.err;
  EXPECT_EQ(skin.err.find("VUID"), std::string::npos) << skin.err;
}

// The Vulkan tracer's distance moments reach the rasterizer: room B of scenes/thin_wall.gltf
// (dark behind a 0.05 m wall; no light reaches it, so all it shows came through the wall in the
// probes) rendered with probes from `--tracer vulkan`, with and without visibility. What remains
// with visibility is the method's (raster.ThinWallTest explains where it comes from): at these
// settings (one update of 128 paths, 15 bounces) 1.40 % of the leak with Vulkan probes and
// 1.35 % with Embree's (measured while writing this). The test allows 5 %: a volume without
// moments would keep all of the leak.
TEST_F(TracerCli, VulkanProbesWithVisibilityStopTheLeakThroughAThinWall) {
  if (!ray_tracing()) GTEST_SKIP() << "the default Vulkan device has no ray-tracing pipelines";
  const auto mean = [&](int visibility) {
    const std::string out = "wall_" + std::to_string(visibility);
    const cli::Result r = run("render " + cli::quote(std::string(DDISH_SOURCE_DIR) + "/scenes/thin_wall.gltf") +
                                  " --width 64 --height 48 --probe-samples 128 --warmup-ms 0 --tonemap linear "
                                  "--tracer vulkan --probe-visibility " + std::to_string(visibility) + " --out " + path(out),
                              "DDISH_VALIDATION=1");
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.err.find("VUID"), std::string::npos) << r.err;
    const ddish::metrics::Image image = ddish::metrics::read_image(dir_ / out / "frame_0000.exr");
    double sum = 0.0;
    for (const glm::vec3& p : image.pixels()) sum += double(p.r + p.g + p.b) / 3.0;
    return sum / double(image.pixels().size());
  };
  const double leak = mean(0);
  const double kept = mean(8);
  std::printf("room B with Vulkan probes: without visibility %.4g, with %.4g (%.3f %% of the leak)\n", leak, kept,
              100.0 * kept / leak);
  EXPECT_GT(leak, 0.0);
  EXPECT_LT(kept, 0.05 * leak) << "with visibility the light stays in room A";
}

TEST_F(TracerCli, AnUnknownTracerIsOneErrorLineAndSoIsVulkanWithoutRayTracing) {
  const cli::Result bad = run("probes " + cli::cornell() + " --tracer optix");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("--tracer"), std::string::npos) << bad.err;
  // On a device without ray tracing (Mesa 22 lavapipe; VK_DRIVER_FILES picks it) `vulkan`
  // cannot run at all.
  if (ray_tracing()) return;
  const cli::Result none = run("probes " + cli::cornell() + " --grid 2,2,2 --probe-samples 16 --tracer vulkan");
  EXPECT_EQ(none.code, 2);
  EXPECT_EQ(none.err.rfind("ddish: error: --tracer vulkan: ", 0), 0u) << none.err;
  EXPECT_EQ(none.err.find('\n'), none.err.size() - 1) << none.err;
}

}  // namespace
