// Driver defects (gpu/driver_quirks.h): how drivers are recognised, and the defects themselves,
// reproduced in a child process so that a crash is a measured outcome, not a lost test run.
// When a driver update removes a defect, its pin fails and the workaround can be re-measured.
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>

#include <gtest/gtest.h>

#include "gpu/commands.h"
#include "gpu/context.h"
#include "gpu/driver_quirks.h"
#include "gpu/image.h"
#include "gpu/timestamps.h"

namespace ddish::gpu::test {
namespace {

DeviceInfo lavapipe(const char* driver_info) {
  DeviceInfo d;
  d.name = "llvmpipe (LLVM 15.0.6, 256 bits)";
  d.driver_name = "llvmpipe";
  d.driver_info = driver_info;
  return d;
}

TEST(DriverQuirks, ReadsTheMesaRelease) {
  const auto v = mesa_version(lavapipe("Mesa 25.0.7-2~bpo12+1 (LLVM 15.0.6)"));
  ASSERT_TRUE(v.has_value());
  EXPECT_EQ(v->major, 25);
  EXPECT_EQ(v->minor, 0);
  const auto old = mesa_version(lavapipe("Mesa 22.3.6 (LLVM 15.0.6)"));
  ASSERT_TRUE(old.has_value());
  EXPECT_EQ(old->major, 22);
  EXPECT_EQ(old->minor, 3);
  EXPECT_FALSE(mesa_version(lavapipe("535.104.05")).has_value());
  EXPECT_FALSE(mesa_version(lavapipe("Mesa x.y")).has_value());
  EXPECT_FALSE(mesa_version(lavapipe("")).has_value());
}

TEST(DriverQuirks, ClassifiesMultiviewByDriverAndRelease) {
  EXPECT_EQ(multiview_defect(lavapipe("Mesa 22.3.6 (LLVM 15.0.6)")),
            MultiviewDefect::clipped_primitives_lose_view);
  EXPECT_EQ(multiview_defect(lavapipe("Mesa 25.0.7-2~bpo12+1 (LLVM 15.0.6)")),
            MultiviewDefect::timestamps_after_pass_overrun);
  EXPECT_EQ(multiview_defect(lavapipe("Mesa 26.1.0")), MultiviewDefect::timestamps_after_pass_overrun);
  EXPECT_EQ(multiview_defect(lavapipe("Mesa 23.1.0")), MultiviewDefect::none);
  DeviceInfo nvidia;
  nvidia.driver_name = "NVIDIA";
  nvidia.driver_info = "535.104.05";
  EXPECT_EQ(multiview_defect(nvidia), MultiviewDefect::none);
  EXPECT_TRUE(describe(MultiviewDefect::none, nvidia).empty());
  EXPECT_NE(describe(MultiviewDefect::timestamps_after_pass_overrun,
                     lavapipe("Mesa 25.0.7")).find("Mesa 25.0.7"),
            std::string::npos);
}

// A two-view multiview pass that draws nothing, then a timestamp into the last query of a
// pool of `queries`: valid Vulkan (the timestamp is outside any render pass instance). With
// `reset_pass` an empty one-view pass follows the multiview one first (the workaround).
void multiview_pass_then_timestamp(std::uint32_t queries, bool reset_pass) {
  Context gpu;
  const Device& device = gpu.device();
  const ImageDesc desc{.width = 8, .height = 8, .layers = 2, .usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT};
  Image image(device, desc);
  const ImageView one_layer = image.make_view(0, 1);
  DeviceHandle<VkQueryPool, vkDestroyQueryPool> pool;
  VkQueryPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  pool_info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  pool_info.queryCount = queries;
  VkQueryPool handle = VK_NULL_HANDLE;
  if (vkCreateQueryPool(device.handle(), &pool_info, nullptr, &handle) != VK_SUCCESS) std::abort();
  pool = {device.handle(), handle};
  CommandRunner runner(device);
  runner.run([&](VkCommandBuffer cmd) {
    vkCmdResetQueryPool(cmd, handle, 0, queries);
    image_barrier(cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                  VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                  VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    color.imageView = image.view();
    color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
    info.renderArea = {{0, 0}, {desc.width, desc.height}};
    info.viewMask = 0b11;
    info.colorAttachmentCount = 1;
    info.pColorAttachments = &color;
    vkCmdBeginRendering(cmd, &info);
    vkCmdEndRendering(cmd);
    if (reset_pass) {
      color.imageView = one_layer.get();
      color.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
      info.viewMask = 0;
      info.layerCount = 1;
      vkCmdBeginRendering(cmd, &info);
      vkCmdEndRendering(cmd);
    }
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, handle, queries - 1);
  });
}

DeviceInfo default_device_info() {
  Context gpu;
  return gpu.device().info();
}

TEST(DriverQuirks, MultiviewTimestampOverrunIsPinned) {
  const DeviceInfo device = default_device_info();
  if (!device.timestamps_supported()) GTEST_SKIP() << device.name << " writes no timestamps";
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  // The workaround holds on every device: an empty one-view pass after the multiview passes.
  EXPECT_EXIT((multiview_pass_then_timestamp(2, true), std::exit(0)), ::testing::ExitedWithCode(0), "");
  if (multiview_defect(device) == MultiviewDefect::timestamps_after_pass_overrun) {
    // The defect: the driver still counts the two views after the pass has ended and writes two
    // queries, the second past the pool's end.
    EXPECT_EXIT(multiview_pass_then_timestamp(2, false), ::testing::KilledBySignal(SIGSEGV), "")
        << device.driver_info << " no longer overruns the query pool: re-measure multiview "
        << "without the reset pass (raster/forward_pass.cpp) and update gpu/driver_quirks.cpp";
  } else {
    EXPECT_EXIT((multiview_pass_then_timestamp(2, false), std::exit(0)), ::testing::ExitedWithCode(0), "");
  }
}

}  // namespace
}  // namespace ddish::gpu::test
