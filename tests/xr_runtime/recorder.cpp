// What the app submitted, written for the tests under DDISH_XR_OUT:
//   session.json  every frame (display time and period, shouldRender, when the app waited,
//                 began, located the views and ended, the located and the submitted eye poses
//                 and FOVs in LOCAL, the image files) and the session's states in order;
//   frame_NNNNNN_left.exr / _right.exr  each submitted eye image, linear: the sRGB-encoded
//                 bytes of the swapchain image decoded (metrics::srgb8_decode).
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>

#include <nlohmann/json.hpp>

#include "functions.h"
#include "metrics/color.h"
#include "metrics/image.h"
#include "metrics/image_io.h"

namespace ddish::xr_runtime {

namespace {

using nlohmann::json;

json view_json(const ViewRecord& v) {
  return {{"position", {v.pose.position.x, v.pose.position.y, v.pose.position.z}},
          {"orientation", {v.pose.orientation.x, v.pose.orientation.y, v.pose.orientation.z, v.pose.orientation.w}},
          {"fov", {v.fov.angleLeft, v.fov.angleRight, v.fov.angleUp, v.fov.angleDown}}};
}

// One-shot command buffer on the session's queue, waited for with a fence.
bool submit_and_wait(Session& s, VkCommandBuffer cmd) {
  VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence = VK_NULL_HANDLE;
  if (vkCreateFence(s.binding.device, &fi, nullptr, &fence) != VK_SUCCESS) return false;
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  bool ok = vkQueueSubmit(s.queue, 1, &submit, fence) == VK_SUCCESS &&
            vkWaitForFences(s.binding.device, 1, &fence, VK_TRUE, UINT64_MAX) == VK_SUCCESS;
  vkDestroyFence(s.binding.device, fence, nullptr);
  return ok;
}

}  // namespace

void write_record(const Session& s) {
  if (s.instance->out.empty()) return;
  json frames = json::array();
  for (const FrameRecord& f : s.frames) {
    json located = json::array(), submitted = json::array();
    for (const ViewRecord& v : f.located) located.push_back(view_json(v));
    for (const ViewRecord& v : f.submitted) submitted.push_back(view_json(v));
    frames.push_back({{"index", f.index},
                      {"predicted_display_time_ns", f.predicted_display_time},
                      {"predicted_display_period_ns", f.predicted_display_period},
                      {"should_render", f.should_render},
                      {"wait_return_ns", f.wait_return},
                      {"begin_ns", f.begin},
                      {"located_ns", f.located_at},
                      {"end_ns", f.end},
                      {"ended", f.ended},
                      {"discarded", f.discarded},
                      {"located", located},
                      {"submitted", submitted},
                      {"images", f.images}});
  }
  const json doc{{"runtime", "ddish headless test runtime"}, {"states", s.states}, {"frames", frames}};
  const auto path = s.instance->out / "session.json";
  std::ofstream out(path);
  out << doc.dump(1) << "\n";
  if (!out) std::fprintf(stderr, "ddish test runtime: cannot write %s\n", path.c_str());
}

std::string record_image(Session& s, Swapchain& chain, std::uint32_t index, const XrRect2Di& rect,
                         const std::filesystem::path& file) {
  const VkDevice dev = s.binding.device;
  const auto w = static_cast<std::uint32_t>(rect.extent.width);
  const auto h = static_cast<std::uint32_t>(rect.extent.height);
  const VkDeviceSize bytes = VkDeviceSize(w) * h * 4;
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  std::string written;
  const auto fail = [&](const char* what) { std::fprintf(stderr, "ddish test runtime: %s\n", what); };
  VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bi.size = bytes;
  bi.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  if (vkCreateBuffer(dev, &bi, nullptr, &buffer) != VK_SUCCESS) {
    fail("cannot create a read-back buffer");
    return {};
  }
  VkMemoryRequirements req{};
  vkGetBufferMemoryRequirements(dev, buffer, &req);
  VkPhysicalDeviceMemoryProperties mp{};
  vkGetPhysicalDeviceMemoryProperties(s.binding.physicalDevice, &mp);
  const VkMemoryPropertyFlags want = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = UINT32_MAX;
  for (std::uint32_t i = 0; i < mp.memoryTypeCount; ++i)
    if ((req.memoryTypeBits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & want) == want) {
      ai.memoryTypeIndex = i;
      break;
    }
  VkCommandBufferAllocateInfo cb{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr, s.pool,
                                 VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
  if (ai.memoryTypeIndex == UINT32_MAX || vkAllocateMemory(dev, &ai, nullptr, &memory) != VK_SUCCESS ||
      vkBindBufferMemory(dev, buffer, memory, 0) != VK_SUCCESS ||
      vkAllocateCommandBuffers(dev, &cb, &cmd) != VK_SUCCESS) {
    fail("cannot allocate read-back memory");
  } else {
    const VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, nullptr,
                                         VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT, nullptr};
    vkBeginCommandBuffer(cmd, &begin);
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    b.oldLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = chain.images[index];
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &b);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageOffset = {rect.offset.x, rect.offset.y, 0};
    region.imageExtent = {w, h, 1};
    vkCmdCopyImageToBuffer(cmd, chain.images[index], VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1, &region);
    // Back to the layout the binding promises the app.
    b.srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    b.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    b.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    b.newLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    VkBufferMemoryBarrier hb{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER};
    hb.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    hb.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    hb.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    hb.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    hb.buffer = buffer;
    hb.size = VK_WHOLE_SIZE;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                         0, 0, nullptr, 1, &hb, 1, &b);
    vkEndCommandBuffer(cmd);
    void* mapped = nullptr;
    if (!submit_and_wait(s, cmd) || vkMapMemory(dev, memory, 0, bytes, 0, &mapped) != VK_SUCCESS) {
      fail("the read-back of a submitted image failed");
    } else {
      const auto* px = static_cast<const std::uint8_t*>(mapped);
      const bool bgr = chain.format == VK_FORMAT_B8G8R8A8_SRGB;
      metrics::Image image(static_cast<int>(w), static_cast<int>(h));
      for (std::uint32_t y = 0; y < h; ++y)
        for (std::uint32_t x = 0; x < w; ++x) {
          const std::uint8_t* p = px + (std::size_t(y) * w + x) * 4;
          image.at(int(x), int(y)) = {metrics::srgb8_decode(p[bgr ? 2 : 0]), metrics::srgb8_decode(p[1]),
                                      metrics::srgb8_decode(p[bgr ? 0 : 2])};
        }
      vkUnmapMemory(dev, memory);
      try {
        metrics::write_exr(file, image);
        written = file.filename().string();
      } catch (const std::exception& e) {
        fail(e.what());
      }
    }
  }
  if (cmd != VK_NULL_HANDLE) vkFreeCommandBuffers(dev, s.pool, 1, &cmd);
  vkDestroyBuffer(dev, buffer, nullptr);
  if (memory != VK_NULL_HANDLE) vkFreeMemory(dev, memory, nullptr);
  return written;
}

}  // namespace ddish::xr_runtime
