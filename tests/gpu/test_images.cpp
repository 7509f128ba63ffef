// Images on the real device: layered (multiview) targets, MSAA with resolve, depth, readback.
// Everything is cleared, not drawn (drawing is raster/'s business), but through the same dynamic
// rendering path a render pass uses, so the attachments, views and barriers are the real ones.
#include <array>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "gpu/buffer.h"
#include "gpu/commands.h"
#include "gpu/format.h"
#include "gpu/image.h"
#include "gpu_test.h"

namespace ddish::gpu::test {
namespace {

using Rgba8 = std::array<std::uint8_t, 4>;

// A float colour whose UNORM8 conversion is exact: k / 255.
VkClearValue colour(Rgba8 c) {
  VkClearValue v{};
  for (int i = 0; i < 4; ++i) v.color.float32[i] = static_cast<float>(c[i]) / 255.0f;
  return v;
}

VkRenderingAttachmentInfo attachment(VkImageView view, VkImageLayout layout, VkClearValue clear) {
  VkRenderingAttachmentInfo info{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  info.imageView = view;
  info.imageLayout = layout;
  info.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  info.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  info.clearValue = clear;
  return info;
}

VkRenderingInfo rendering(const ImageDesc& desc, std::uint32_t view_mask) {
  VkRenderingInfo info{VK_STRUCTURE_TYPE_RENDERING_INFO};
  info.renderArea = {{0, 0}, {desc.width, desc.height}};
  info.layerCount = view_mask != 0 ? 0 : 1;  // with multiview the view mask says which layers
  info.viewMask = view_mask;
  return info;
}

// Moves `image` from `layout` (last written at `stage` with `access`) to transfer source, copies
// its first `layers` layers one after another into `out`, and makes the copy visible to the host.
void copy_layers_to_host(VkCommandBuffer cmd, const Image& image, VkImageLayout layout,
                         VkPipelineStageFlags stage, VkAccessFlags access, const Buffer& out,
                         std::uint32_t layers = 1) {
  image_barrier(cmd, image, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, stage, access,
                VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
  for (std::uint32_t layer = 0; layer < layers; ++layer)
    copy_image_to_buffer(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layer, out,
                         layer * image.layer_bytes());
  memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                 VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
}

void expect_all_texels(const std::vector<Rgba8>& texels, Rgba8 expected, const char* what) {
  std::size_t wrong = 0;
  for (const Rgba8& t : texels) wrong += t != expected;
  EXPECT_EQ(wrong, 0u) << what << ": first texel " << int(texels[0][0]) << "," << int(texels[0][1])
                       << "," << int(texels[0][2]) << "," << int(texels[0][3]);
}

class Images : public GpuTest {};

TEST(Formats, AspectsAndSizes) {
  EXPECT_EQ(aspect_flags(VK_FORMAT_R8G8B8A8_UNORM), VkImageAspectFlags{VK_IMAGE_ASPECT_COLOR_BIT});
  EXPECT_EQ(aspect_flags(VK_FORMAT_D32_SFLOAT), VkImageAspectFlags{VK_IMAGE_ASPECT_DEPTH_BIT});
  EXPECT_EQ(aspect_flags(VK_FORMAT_D24_UNORM_S8_UINT),
            VkImageAspectFlags{VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT});
  EXPECT_EQ(texel_bytes(VK_FORMAT_R8G8B8A8_SRGB), 4u);
  EXPECT_EQ(texel_bytes(VK_FORMAT_R16G16B16A16_SFLOAT), 8u);
  EXPECT_EQ(texel_bytes(VK_FORMAT_R32G32B32A32_SFLOAT), 16u);
  EXPECT_EQ(texel_bytes(VK_FORMAT_D16_UNORM), 2u);
  EXPECT_THROW(texel_bytes(VK_FORMAT_BC1_RGB_UNORM_BLOCK), GpuError);
}

TEST_F(Images, LayersClearSeparatelyAndReadBack) {
  const ImageDesc desc{.width = 37, .height = 21, .layers = 3};
  Image image(device(), desc);
  EXPECT_EQ(image.layer_bytes(), 37u * 21u * 4u);
  Buffer out(device(), 3 * image.layer_bytes(), 0, MemoryUse::readback);
  const std::array<Rgba8, 3> colours = {{{255, 0, 0, 255}, {0, 51, 102, 255}, {1, 2, 3, 4}}};
  CommandRunner runner(device());
  runner.run([&](VkCommandBuffer cmd) {
    image_barrier(cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
                  VK_ACCESS_TRANSFER_WRITE_BIT);
    for (std::uint32_t layer = 0; layer < 3; ++layer) {
      const VkClearColorValue clear = colour(colours[layer]).color;
      const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, layer, 1};
      vkCmdClearColorImage(cmd, image.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &clear, 1,
                           &range);
    }
    copy_layers_to_host(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                        VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT, out, 3);
  });
  const std::size_t texels = 37 * 21;
  for (std::uint32_t layer = 0; layer < 3; ++layer)
    expect_all_texels(out.read<Rgba8>(texels, layer * image.layer_bytes()), colours[layer],
                      "layer");
  EXPECT_EQ(image.view(), VK_NULL_HANDLE);  // transfer-only: Vulkan allows it no views
  EXPECT_THROW(image.make_view(0, 1), GpuError);
}

TEST_F(Images, ViewsOfLayerRanges) {
  Image image(device(), {.width = 4, .height = 4, .layers = 3, .usage = VK_IMAGE_USAGE_SAMPLED_BIT});
  EXPECT_NE(image.view(), VK_NULL_HANDLE);
  EXPECT_TRUE(static_cast<bool>(image.make_view(1, 2)));
  EXPECT_TRUE(static_cast<bool>(image.make_view(2, 1)));
  EXPECT_THROW(image.make_view(2, 2), GpuError);
  EXPECT_THROW(image.make_view(0, 0), GpuError);
}

TEST_F(Images, MultiviewRenderingClearsEveryViewLayer) {
  ASSERT_TRUE(device().features().dynamic_rendering && device().features().multiview);
  const std::uint32_t views = std::min(device().info().max_multiview_view_count, 6u);
  const ImageDesc desc{.width = 16, .height = 9, .layers = views,
                       .usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT};
  Image image(device(), desc);
  Buffer out(device(), views * image.layer_bytes(), 0, MemoryUse::readback);
  const Rgba8 sky = {51, 102, 153, 255};
  CommandRunner runner(device());
  runner.run([&](VkCommandBuffer cmd) {
    image_barrier(cmd, image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                  VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0,
                  VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                  VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    const VkRenderingAttachmentInfo target =
        attachment(image.view(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, colour(sky));
    VkRenderingInfo info = rendering(desc, (1u << views) - 1);
    info.colorAttachmentCount = 1;
    info.pColorAttachments = &target;
    vkCmdBeginRendering(cmd, &info);
    vkCmdEndRendering(cmd);
    copy_layers_to_host(cmd, image, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                        VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, out, views);
  });
  for (std::uint32_t layer = 0; layer < views; ++layer)
    expect_all_texels(out.read<Rgba8>(16 * 9, layer * image.layer_bytes()), sky, "view layer");
}

TEST_F(Images, MsaaColourResolves) {
  ASSERT_TRUE(device().features().dynamic_rendering);
  ASSERT_NE(device().info().msaa_sample_counts() & VK_SAMPLE_COUNT_4_BIT, 0u);
  const ImageDesc msaa_desc{.width = 8, .height = 8,
                            .usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT |
                                     VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT,
                            .samples = VK_SAMPLE_COUNT_4_BIT};
  const ImageDesc resolved_desc{.width = 8, .height = 8,
                                .usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT};
  Image msaa(device(), msaa_desc);
  Image resolved(device(), resolved_desc);
  Buffer out(device(), resolved.layer_bytes(), 0, MemoryUse::readback);
  const Rgba8 grey = {102, 102, 102, 255};

  CommandRunner runner(device());
  runner.run([&](VkCommandBuffer cmd) {
    for (const Image* target : {&msaa, &resolved})
      image_barrier(cmd, *target, VK_IMAGE_LAYOUT_UNDEFINED,
                    VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
                    0, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                    VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT);
    VkRenderingAttachmentInfo target =
        attachment(msaa.view(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, colour(grey));
    target.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;  // only the resolve is kept
    target.resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
    target.resolveImageView = resolved.view();
    target.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    VkRenderingInfo info = rendering(msaa_desc, 0);
    info.colorAttachmentCount = 1;
    info.pColorAttachments = &target;
    vkCmdBeginRendering(cmd, &info);
    vkCmdEndRendering(cmd);
    copy_layers_to_host(cmd, resolved, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                        VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, out);
  });
  expect_all_texels(out.read<Rgba8>(64), grey, "resolved MSAA");
  // Multisampled images are rejected before anything is recorded.
  EXPECT_THROW(copy_image_to_buffer(VK_NULL_HANDLE, msaa, VK_IMAGE_LAYOUT_GENERAL, 0, out),
               GpuError);
}

TEST_F(Images, DepthClearsAndReadsBack) {
  ASSERT_TRUE(device().features().dynamic_rendering);
  const ImageDesc desc{.width = 8, .height = 8, .format = VK_FORMAT_D32_SFLOAT,
                       .usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT};
  Image depth(device(), desc);
  Buffer out(device(), depth.layer_bytes(), 0, MemoryUse::readback);
  VkClearValue clear{};
  clear.depthStencil = {0.375f, 0};
  constexpr VkPipelineStageFlags tests =
      VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;

  CommandRunner runner(device());
  runner.run([&](VkCommandBuffer cmd) {
    image_barrier(cmd, depth, VK_IMAGE_LAYOUT_UNDEFINED,
                  VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0,
                  tests, VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT);
    const VkRenderingAttachmentInfo target =
        attachment(depth.view(), VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, clear);
    VkRenderingInfo info = rendering(desc, 0);
    info.pDepthAttachment = &target;
    vkCmdBeginRendering(cmd, &info);
    vkCmdEndRendering(cmd);
    copy_layers_to_host(cmd, depth, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, tests,
                        VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, out);
  });
  for (float d : out.read<float>(64)) ASSERT_EQ(d, 0.375f);
}

TEST_F(Images, UnsupportedRequestsAreOneClearLine) {
  EXPECT_THROW(Image(device(), ImageDesc{.width = 0, .height = 4}), GpuError);
  const std::uint32_t max_layers = device().limits().maxImageArrayLayers;
  try {
    Image(device(), ImageDesc{.width = 4, .height = 4, .layers = max_layers + 1});
    FAIL() << "an image with too many layers was created";
  } catch (const GpuError& e) {
    EXPECT_NE(std::string(e.what()).find(std::to_string(max_layers + 1) + " layers"),
              std::string::npos)
        << e.what();
  }
  if ((device().info().color_sample_counts & VK_SAMPLE_COUNT_64_BIT) == 0) {
    try {
      Image(device(), ImageDesc{.width = 4, .height = 4,
                                .usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT,
                                .samples = VK_SAMPLE_COUNT_64_BIT});
      FAIL() << "a 64x MSAA image was created";
    } catch (const GpuError& e) {
      EXPECT_NE(std::string(e.what()).find("64 samples per pixel are not supported"),
                std::string::npos)
          << e.what();
    }
  }
}

}  // namespace
}  // namespace ddish::gpu::test
