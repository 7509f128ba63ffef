// --every=N writes frames N-1, 2N-1, ... and the last, only those are read back from the GPU,
// and --timings records per frame what the process holds (resident memory, open descriptors,
// live Vulkan allocations): the figures the soak run (scripts/results/soak.py) checks for growth.
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"

namespace {

namespace fs = std::filesystem;
using cli::quote;
using cli::Result;

class EveryCli : public cli::TempDirTest {
 protected:
  EveryCli() : TempDirTest("ddish_every_cli_") {}
};

TEST_F(EveryCli, EveryNthFrameAndTheLastAreWrittenAndResourcesAreRecorded) {
  const std::string scene = quote(std::string(DDISH_SOURCE_DIR) + "/scenes/cornell_box.gltf");
  Result r = run("render " + scene + " --width 16 --height 16 --msaa 1 --grid 2,2,2 --probe-samples 4 "
                 "--warmup-ms 0 --frames 8 --every=3 --out " + path("out") + " --timings " + path("t.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  std::set<std::string> pngs;
  for (const auto& e : fs::directory_iterator(dir_ / "out"))
    if (e.path().extension() == ".png") pngs.insert(e.path().filename().string());
  EXPECT_EQ(pngs, (std::set<std::string>{"frame_0002.png", "frame_0005.png", "frame_0007.png"}));

  std::ifstream in(dir_ / "t.json");
  const nlohmann::json doc = nlohmann::json::parse(in);
  ASSERT_EQ(doc.at("frames").size(), 8u);
  for (const auto& f : doc["frames"]) {
    const auto& res = f.at("resources");
    EXPECT_GT(res.at("rss_kb").get<long long>(), 1000);  // a Vulkan process holds megabytes
    EXPECT_GE(res.at("open_fds").get<int>(), 3);          // stdin, stdout, stderr at least
    EXPECT_GT(res.at("gpu_allocations").get<long long>(), 0);
    EXPECT_GT(res.at("gpu_bytes").get<long long>(), 0);
  }
  // Only the written frames came back to the CPU (readback is the CPU's conversion of them).
  for (std::size_t k = 0; k < 8; ++k) {
    const bool written = k == 2 || k == 5 || k == 7;
    EXPECT_EQ(doc["frames"][k].at("read_back").get<bool>(), written) << k;
    EXPECT_EQ(doc["frames"][k]["stages_ms"]["readback"].get<double>() > 0.0, written) << k;
  }
  // Nothing is allocated per frame on the device: the tally is the same after every frame.
  EXPECT_EQ(doc["frames"][1]["resources"]["gpu_allocations"], doc["frames"][7]["resources"]["gpu_allocations"]);
  // The summary comes after the frames, the last frame's late stage (the writer's drain) in it.
  EXPECT_TRUE(doc.at("summary").contains("output_drain"));
  EXPECT_TRUE(doc["frames"][7]["stages_ms"].contains("output_drain"));

  r = run("render " + scene + " --every=0 --frames 2");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--every"), std::string::npos) << r.err;
}

}  // namespace
