// The compute path end to end on the real device: SPIR-V from the build, a pipeline with a
// storage buffer and push constants, a dispatch, a readback checked value by value.
#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "gpu/buffer.h"
#include "gpu/commands.h"
#include "gpu/compute_pipeline.h"
#include "gpu/shader.h"
#include "gpu/timestamps.h"
#include "gpu/transfer.h"
#include "gpu_test.h"

namespace ddish::gpu::test {
namespace {

struct FillParams {
  std::uint32_t count;
  std::uint32_t offset;
};

constexpr std::uint32_t kGroupSize = 64;  // local_size_x of fill_pattern.comp
constexpr std::uint32_t kSentinel = 0xDEADBEEF;

class Compute : public GpuTest {
 protected:
  // Records the fill of `count` values into `out`, then makes the writes visible to the host
  // and to transfers.
  void record_fill(VkCommandBuffer cmd, const ComputePipeline& fill, FillParams params) {
    fill.bind(cmd);
    fill.push(cmd, params);
    fill.dispatch(cmd, group_count(params.count, kGroupSize));
    memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                   VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                   VK_ACCESS_HOST_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT);
  }

  ComputePipeline make_fill() {
    return ComputePipeline(device(), ShaderModule::load(device(), "fill_pattern.comp"),
                           {.storage_buffers = 1, .push_constant_bytes = sizeof(FillParams)});
  }
};

void expect_pattern(const std::vector<std::uint32_t>& values, std::uint32_t count,
                    std::uint32_t offset) {
  ASSERT_GT(values.size(), count);
  std::uint32_t wrong = 0;
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::uint32_t expected = i * i + offset;  // wraps mod 2^32 like the shader's uint
    if (values[i] != expected && ++wrong <= 5)
      ADD_FAILURE() << "values[" << i << "] = " << values[i] << ", expected " << expected;
  }
  EXPECT_EQ(wrong, 0u);
  for (std::size_t i = count; i < values.size(); ++i)
    ASSERT_EQ(values[i], kSentinel) << "written past count at " << i;
}

TEST_F(Compute, FillPatternWritesEveryValue) {
  // Not a multiple of the group size, and past 65536 so that i*i wraps.
  constexpr std::uint32_t count = 100'003;
  constexpr std::uint32_t capacity = count + 61;
  Buffer out(device(), capacity * sizeof(std::uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
             MemoryUse::readback);
  ASSERT_TRUE(out.host_visible());
  out.write(std::span<const std::uint32_t>(std::vector<std::uint32_t>(capacity, kSentinel)));

  ComputePipeline fill = make_fill();
  fill.bind_buffers({&out});
  CommandRunner runner(device());

  runner.run([&](VkCommandBuffer cmd) { record_fill(cmd, fill, {count, 7}); });
  expect_pattern(out.read<std::uint32_t>(capacity), count, 7);

  // The same pipeline again, with other push constants: nothing stale survives.
  runner.run([&](VkCommandBuffer cmd) { record_fill(cmd, fill, {count, 1'000'000}); });
  expect_pattern(out.read<std::uint32_t>(capacity), count, 1'000'000);
}

TEST_F(Compute, DeviceLocalResultsComeBackThroughDownload) {
  constexpr std::uint32_t count = 4096;
  constexpr std::uint32_t capacity = count + 1;
  Buffer out(device(), capacity * sizeof(std::uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
             MemoryUse::device_local);
  CommandRunner runner(device());
  const std::vector<std::uint32_t> sentinels(capacity, kSentinel);
  upload(device(), runner, out, std::span<const std::uint32_t>(sentinels));

  ComputePipeline fill = make_fill();
  fill.bind_buffers({&out});
  runner.run([&](VkCommandBuffer cmd) { record_fill(cmd, fill, {count, 3}); });
  expect_pattern(download<std::uint32_t>(device(), runner, out, capacity), count, 3);
}

TEST_F(Compute, TimestampsMeasureTheDispatch) {
  ASSERT_TRUE(device().info().timestamps_supported());
  constexpr std::uint32_t count = 1 << 16;
  Buffer out(device(), count * sizeof(std::uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
             MemoryUse::device_local);
  ComputePipeline fill = make_fill();
  fill.bind_buffers({&out});
  TimestampQueries timer(device(), 2);
  CommandRunner runner(device());
  runner.run([&](VkCommandBuffer cmd) {
    timer.reset(cmd);
    timer.begin(cmd, 0);
    fill.bind(cmd);
    fill.push(cmd, FillParams{count, 0});
    fill.dispatch(cmd, group_count(count, kGroupSize));
    timer.end(cmd, 0);
    timer.begin(cmd, 1);  // an empty range
    timer.end(cmd, 1);
  });
  const double dispatch_ms = timer.milliseconds(0);
  EXPECT_TRUE(std::isfinite(dispatch_ms));
  EXPECT_GE(dispatch_ms, 0.0);
  EXPECT_LT(dispatch_ms, 60'000.0);  // the 64k-value fill cannot take a minute: ticks are sane
  const std::vector<double> all = timer.all_milliseconds();
  ASSERT_EQ(all.size(), 2u);
  EXPECT_DOUBLE_EQ(all[0], dispatch_ms);
  EXPECT_TRUE(std::isfinite(all[1]));
  EXPECT_GE(all[1], 0.0);
  EXPECT_THROW(timer.milliseconds(2), GpuError);
}

TEST_F(Compute, PipelineRejectsWrongBindingsAndPushes) {
  ComputePipeline fill = make_fill();
  Buffer a(device(), 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::upload);
  Buffer b(device(), 64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::upload);
  EXPECT_THROW(fill.bind_buffers({&a, &b}), GpuError);
  EXPECT_THROW(fill.bind_buffers({nullptr}), GpuError);
  const ShaderModule shader = ShaderModule::load(device(), "fill_pattern.comp");
  EXPECT_THROW(ComputePipeline(device(), shader, {.storage_buffers = 1, .push_constant_bytes = 6}),
               GpuError);
  CommandRunner runner(device());
  const std::uint32_t too_big[3] = {1, 2, 3};
  EXPECT_THROW(runner.run([&](VkCommandBuffer cmd) { fill.push(cmd, too_big); }), GpuError);
}

}  // namespace
}  // namespace ddish::gpu::test
