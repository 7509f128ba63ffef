#include "metrics/timing.h"

#include <stdexcept>

#include <gtest/gtest.h>

#include "test_util.h"

namespace ddish::metrics {
namespace {

TEST(Timing, StagesAccumulateInOrder) {
  FrameTimings f;
  f.frame = 3;
  f.add("probe_update", 10.0);
  f.add("raster", 4.0);
  f.add("probe_update", 2.5);  // a second run of a stage adds up
  ASSERT_EQ(f.stages.size(), 2u);
  EXPECT_EQ(f.stages[0].name, "probe_update");
  EXPECT_DOUBLE_EQ(f.stage_ms("probe_update"), 12.5);
  EXPECT_DOUBLE_EQ(f.stage_ms("absent"), 0.0);
  EXPECT_DOUBLE_EQ(f.total_ms(), 16.5);
  EXPECT_THROW(f.add("bad", -1.0), std::invalid_argument);
}

TEST(Timing, StageTimerRecordsOnce) {
  FrameTimings f;
  {
    StageTimer t(f, "scope");
    double ms = t.stop();
    EXPECT_GE(ms, 0.0);
    EXPECT_EQ(t.stop(), 0.0);
  }  // the destructor must not add a second time
  ASSERT_EQ(f.stages.size(), 1u);
  { StageTimer t(f, "scope"); }
  EXPECT_EQ(f.stages.size(), 1u);
  EXPECT_GE(f.stage_ms("scope"), 0.0);
}

TEST(Timing, JsonHasFramesAndSummary) {
  TimingLog log;
  for (int i = 0; i < 3; ++i) {
    FrameTimings f;
    f.frame = i;
    f.add("probes", 10.0 + i);
    if (i != 1) f.add("raster", 2.0 * i);
    log.add(f);
  }
  nlohmann::ordered_json j = log.to_json();
  ASSERT_EQ(j["frames"].size(), 3u);
  EXPECT_EQ(j["frames"][2]["frame"], 2);
  EXPECT_DOUBLE_EQ(j["frames"][2]["stages_ms"]["raster"].get<double>(), 4.0);
  EXPECT_DOUBLE_EQ(j["frames"][2]["total_ms"].get<double>(), 16.0);
  EXPECT_EQ(j["frames"][1]["stages_ms"].size(), 1u);
  EXPECT_EQ(j["summary"]["probes"]["frames"], 3);
  EXPECT_DOUBLE_EQ(j["summary"]["probes"]["mean_ms"].get<double>(), 11.0);
  EXPECT_DOUBLE_EQ(j["summary"]["probes"]["min_ms"].get<double>(), 10.0);
  EXPECT_DOUBLE_EQ(j["summary"]["probes"]["max_ms"].get<double>(), 12.0);
  EXPECT_EQ(j["summary"]["raster"]["frames"], 2);
  EXPECT_DOUBLE_EQ(j["summary"]["raster"]["mean_ms"].get<double>(), 2.0);
}

TEST(Timing, FileRoundTrip) {
  auto path = testing::scratch_dir() / "timings.json";
  TimingLog log;
  FrameTimings f;
  f.frame = 7;
  f.add("zeta", 1.25);
  f.add("alpha", 0.5);
  log.add(f);
  log.write(path);
  TimingLog back = TimingLog::read(path);
  ASSERT_EQ(back.frames().size(), 1u);
  EXPECT_EQ(back.frames()[0].frame, 7);
  ASSERT_EQ(back.frames()[0].stages.size(), 2u);
  EXPECT_EQ(back.frames()[0].stages[0].name, "zeta");  // recorded order, not sorted
  EXPECT_DOUBLE_EQ(back.frames()[0].stage_ms("alpha"), 0.5);
  EXPECT_THROW(TimingLog::from_json(nlohmann::ordered_json{{"frames", 3}}),
               std::invalid_argument);
}

}  // namespace
}  // namespace ddish::metrics
