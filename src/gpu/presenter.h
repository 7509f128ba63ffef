// Shows a frame of packed RGBA8 display values (R in the low byte, row 0 at the top: what the
// renderer's tonemap and display/gpu_compositor write) in a swapchain, one frame at a time:
//   acquire an image → [the caller's commands, e.g. the compose pass] → copy the frame into a
//   persistent RGBA8 image → clear the swapchain image black and blit the frame into it, 1:1
//   when it fits (nearest: the window then shows the frame's bytes unchanged), else scaled
//   down to fit, centred, aspect kept (linear) → present → wait.
// Waiting for each frame keeps it simple and matches the renderer, which waits for its own
// submission too. Out-of-date and suboptimal swapchains are made again; a minimised window
// (no area) skips presenting until it has one.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu/handle.h"
#include "gpu/image.h"
#include "gpu/swapchain.h"

namespace ddish::gpu {

class Buffer;
class Device;

enum class PresentStatus {
  presented,
  minimised,    // the surface has no area: nothing shown
  out_of_date,  // the swapchain was made again; this frame was not shown
};

// Where the frame lands in the swapchain image: the rectangle it is blitted to.
struct PresentPlacement {
  std::int32_t x = 0, y = 0;
  std::uint32_t width = 0, height = 0;
  bool scaled = false;
};

// The rectangle a frame of frame_w × frame_h takes in a target of target_w × target_h: 1:1 and
// centred when it fits, else the largest aspect-keeping size that fits, centred.
PresentPlacement place_frame(std::uint32_t frame_w, std::uint32_t frame_h, std::uint32_t target_w,
                             std::uint32_t target_h);

class Presenter {
 public:
  // Throws GpuError as Swapchain does.
  Presenter(const Device& device, VkSurfaceKHR surface, VkExtent2D drawable, bool mailbox);
  ~Presenter();
  Presenter(const Presenter&) = delete;
  Presenter& operator=(const Presenter&) = delete;

  // The window's drawable size changed: the swapchain is made again before the next frame.
  void resize(VkExtent2D drawable);

  // Presents `frame` (width × height packed RGBA8, a transfer source). `before` (optional) is
  // recorded first into the same command buffer: the pass that writes `frame`.
  PresentStatus present(const Buffer& frame, std::uint32_t width, std::uint32_t height,
                        const std::function<void(VkCommandBuffer)>& before = {});

  const Swapchain& swapchain() const { return *swapchain_; }
  const PresentPlacement& last_placement() const { return placement_; }

 private:
  void ensure_frame_image(std::uint32_t width, std::uint32_t height);
  void rebuild();

  const Device& device_;
  VkExtent2D drawable_;
  bool stale_ = false;  // resize() asked for a new swapchain
  std::unique_ptr<Swapchain> swapchain_;
  DeviceHandle<VkCommandPool, vkDestroyCommandPool> pool_;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  DeviceHandle<VkFence, vkDestroyFence> fence_;
  DeviceHandle<VkSemaphore, vkDestroySemaphore> acquired_;
  std::vector<DeviceHandle<VkSemaphore, vkDestroySemaphore>> rendered_;  // one per swapchain image
  Image frame_image_;
  PresentPlacement placement_;
};

}  // namespace ddish::gpu
