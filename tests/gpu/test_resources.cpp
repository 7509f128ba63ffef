// Buffers, memory-type selection, transfers, one-shot submission and SPIR-V loading.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>

#include "gpu/buffer.h"
#include "gpu/commands.h"
#include "gpu/memory.h"
#include "gpu/shader.h"
#include "gpu/transfer.h"
#include "gpu_test.h"

namespace ddish::gpu::test {
namespace {

VkPhysicalDeviceMemoryProperties three_types() {
  VkPhysicalDeviceMemoryProperties props{};
  props.memoryTypeCount = 3;
  props.memoryTypes[0].propertyFlags = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
  props.memoryTypes[1].propertyFlags =
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  props.memoryTypes[2].propertyFlags = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                       VK_MEMORY_PROPERTY_HOST_COHERENT_BIT |
                                       VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
  return props;
}

std::uint32_t type_for(const VkPhysicalDeviceMemoryProperties& props, std::uint32_t bits,
                       MemoryUse use) {
  return find_memory_type(props, bits, required_properties(use), preferred_properties(use));
}

TEST(MemoryTypes, EachUseGetsTheRightType) {
  const auto props = three_types();
  EXPECT_EQ(type_for(props, 0b111, MemoryUse::device_local), 0u);
  EXPECT_EQ(type_for(props, 0b111, MemoryUse::upload), 1u);
  EXPECT_EQ(type_for(props, 0b111, MemoryUse::readback), 2u);
  // Without a cached type, readback falls back to plain host-visible memory.
  EXPECT_EQ(type_for(props, 0b011, MemoryUse::readback), 1u);
  // The resource's type bits rule: nothing host visible allowed -> a clear error.
  EXPECT_THROW(type_for(props, 0b001, MemoryUse::upload), GpuError);
  EXPECT_THROW(type_for(props, 0b110, MemoryUse::device_local), GpuError);
}

class Resources : public GpuTest {};

TEST_F(Resources, HostVisibleBufferRoundTrip) {
  Buffer buffer(device(), 256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::upload);
  EXPECT_EQ(buffer.size(), 256u);
  EXPECT_GE(buffer.memory().size(), 256u);
  ASSERT_TRUE(buffer.host_visible());
  const std::vector<float> values = {1.5f, -2.0f, 3.25f};
  buffer.write(std::span<const float>(values), 16);
  EXPECT_EQ(buffer.read<float>(3, 16), values);
  EXPECT_THROW(buffer.write(values.data(), 12, 250), GpuError);
  EXPECT_THROW(buffer.read<float>(65), GpuError);

  Buffer moved = std::move(buffer);
  EXPECT_EQ(buffer.handle(), VK_NULL_HANDLE);  // the moved-from buffer owns nothing
  EXPECT_EQ(moved.read<float>(3, 16), values);
}

// The live tally a soak run watches: one allocation per buffer, moved with it, freed with it.
TEST_F(Resources, LiveDeviceMemoryCountsEveryAllocationOnce) {
  const MemoryTally before = live_device_memory();
  {
    Buffer a(device(), 4096, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::upload);
    const MemoryTally one = live_device_memory();
    EXPECT_EQ(one.allocations, before.allocations + 1);
    EXPECT_EQ(one.bytes, before.bytes + static_cast<std::int64_t>(a.memory().size()));
    Buffer b = std::move(a);
    EXPECT_EQ(live_device_memory().allocations, one.allocations);  // moved, not copied
    b = Buffer(device(), 256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::upload);
    EXPECT_EQ(live_device_memory().allocations, one.allocations);  // the old one was freed
  }
  EXPECT_EQ(live_device_memory().allocations, before.allocations);
  EXPECT_EQ(live_device_memory().bytes, before.bytes);
}

TEST_F(Resources, EmptyBufferIsAnError) {
  EXPECT_THROW(Buffer(device(), 0, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::upload),
               GpuError);
}

TEST_F(Resources, GpuCopyBetweenBuffers) {
  constexpr std::uint32_t n = 1000;
  std::vector<std::uint32_t> values(n);
  std::iota(values.begin(), values.end(), 17u);
  Buffer src(device(), n * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::upload);
  Buffer dst(device(), n * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::readback);
  src.write(std::span<const std::uint32_t>(values));
  CommandRunner runner(device());
  runner.run([&](VkCommandBuffer cmd) {
    copy_buffer(cmd, src, dst, 400 * 4, 100 * 4, 0);  // values[100..499] to the start
    memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
  });
  const std::vector<std::uint32_t> copied = dst.read<std::uint32_t>(400);
  for (std::uint32_t i = 0; i < 400; ++i) ASSERT_EQ(copied[i], 117u + i) << i;
}

TEST_F(Resources, DeviceLocalUploadAndDownload) {
  std::vector<std::int32_t> values(3000);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<std::int32_t>(i) * -3;
  Buffer buffer(device(), values.size() * 4, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT,
                MemoryUse::device_local);
  CommandRunner runner(device());
  upload(device(), runner, buffer, std::span<const std::int32_t>(values));
  EXPECT_EQ(download<std::int32_t>(device(), runner, buffer, values.size()), values);
  EXPECT_THROW(download<std::int32_t>(device(), runner, buffer, values.size() + 1), GpuError);
}

TEST_F(Resources, RunnerPropagatesRecordingErrorsAndStaysUsable) {
  CommandRunner runner(device());
  EXPECT_THROW(runner.run([](VkCommandBuffer) { throw std::runtime_error("recording failed"); }),
               std::runtime_error);
  Buffer buffer(device(), 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::readback);
  runner.run([&](VkCommandBuffer cmd) {
    vkCmdFillBuffer(cmd, buffer.handle(), 0, 16, 0x01020304u);
    memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
  });
  EXPECT_EQ(buffer.read<std::uint32_t>(4), std::vector<std::uint32_t>(4, 0x01020304u));
}

TEST(Shaders, BuildTreeHoldsTheCompiledShader) {
  const std::vector<std::uint32_t> code = load_spirv(shader_path("fill_pattern.comp"));
  ASSERT_GT(code.size(), 5u);
  EXPECT_EQ(code[0], 0x07230203u);
}

TEST(Shaders, MissingFileNamesThePath) {
  const std::filesystem::path missing = shader_dir() / "no_such_shader.comp.spv";
  try {
    load_spirv(missing);
    FAIL() << "a missing file loaded";
  } catch (const GpuError& e) {
    EXPECT_NE(std::string(e.what()).find("SPIR-V file not found: " + missing.string()),
              std::string::npos)
        << e.what();
  }
}

TEST(Shaders, EnvironmentOverridesTheDirectory) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("ddish_gpu_test_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  {
    std::ofstream(dir / "broken.comp.spv", std::ios::binary) << "not spir-v";  // 11 bytes
    std::ofstream(dir / "bad_magic.comp.spv", std::ios::binary) << "12345678";
  }
  {
    ScopedEnv env("DDISH_SHADER_DIR", dir.string());
    EXPECT_EQ(shader_dir(), dir);
    EXPECT_EQ(shader_path("x.comp"), dir / "x.comp.spv");
    EXPECT_THROW(load_spirv(shader_path("fill_pattern.comp")), GpuError);  // not in that dir
    EXPECT_THROW(load_spirv(shader_path("broken.comp")), GpuError);
    try {
      load_spirv(shader_path("bad_magic.comp"));
      FAIL() << "bad magic accepted";
    } catch (const GpuError& e) {
      EXPECT_NE(std::string(e.what()).find("bad magic"), std::string::npos) << e.what();
    }
  }
  {
    ScopedEnv env("DDISH_SHADER_DIR", "");  // empty means unset
    EXPECT_EQ(shader_dir(), std::filesystem::path(DDISH_SHADER_DIR));
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ddish::gpu::test
