// Swapchains: real VkImages on the app's device (the session's binding), in the layouts the
// Vulkan binding promises: VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL when an image is handed to
// the app (xrWaitSwapchainImage), and the app must give it back in that layout. The runtime
// reads a shown image (recorder.cpp) with a transfer and returns it to that layout.
#include <algorithm>

#include "functions.h"

namespace ddish::xr_runtime {

namespace {

constexpr VkFormat kFormats[] = {VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_B8G8R8A8_SRGB};

Swapchain* chain_of(XrSwapchain h) {
  return runtime().get<Swapchain>(reinterpret_cast<std::uintptr_t>(h), Kind::swapchain);
}

std::uint32_t memory_type(VkPhysicalDevice pd, std::uint32_t bits, VkMemoryPropertyFlags want) {
  VkPhysicalDeviceMemoryProperties mp{};
  vkGetPhysicalDeviceMemoryProperties(pd, &mp);
  for (std::uint32_t i = 0; i < mp.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & want) == want) return i;
  return UINT32_MAX;
}

}  // namespace

XrResult make_images(Session& s, Swapchain& chain, VkImageUsageFlags usage) {
  const VkDevice dev = s.binding.device;
  for (std::uint32_t i = 0; i < kSwapchainLength; ++i) {
    VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    ci.imageType = VK_IMAGE_TYPE_2D;
    ci.format = chain.format;
    ci.extent = {chain.width, chain.height, 1};
    ci.mipLevels = 1;
    ci.arrayLayers = 1;
    ci.samples = VK_SAMPLE_COUNT_1_BIT;
    ci.tiling = VK_IMAGE_TILING_OPTIMAL;
    ci.usage = usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;  // the runtime reads what it shows
    ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkImage image = VK_NULL_HANDLE;
    if (vkCreateImage(dev, &ci, nullptr, &image) != VK_SUCCESS) return XR_ERROR_RUNTIME_FAILURE;
    chain.images.push_back(image);
    VkMemoryRequirements req{};
    vkGetImageMemoryRequirements(dev, image, &req);
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    ai.memoryTypeIndex = memory_type(s.binding.physicalDevice, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (ai.memoryTypeIndex == UINT32_MAX) return XR_ERROR_RUNTIME_FAILURE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    if (vkAllocateMemory(dev, &ai, nullptr, &memory) != VK_SUCCESS) return XR_ERROR_RUNTIME_FAILURE;
    chain.memory.push_back(memory);
    if (vkBindImageMemory(dev, image, memory, 0) != VK_SUCCESS) return XR_ERROR_RUNTIME_FAILURE;
  }
  // UNDEFINED -> COLOR_ATTACHMENT_OPTIMAL for every image, once, on the app's queue.
  VkCommandBufferAllocateInfo cb{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr, s.pool,
                                 VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  if (vkAllocateCommandBuffers(dev, &cb, &cmd) != VK_SUCCESS) return XR_ERROR_RUNTIME_FAILURE;
  const VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO, nullptr,
                                       VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT, nullptr};
  vkBeginCommandBuffer(cmd, &begin);
  std::vector<VkImageMemoryBarrier> barriers;
  for (VkImage image : chain.images) {
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = 0;
    b.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    b.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    b.newLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = image;
    b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    barriers.push_back(b);
  }
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0,
                       nullptr, static_cast<std::uint32_t>(barriers.size()), barriers.data());
  vkEndCommandBuffer(cmd);
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  VkResult r = vkQueueSubmit(s.queue, 1, &submit, VK_NULL_HANDLE);
  if (r == VK_SUCCESS) r = vkQueueWaitIdle(s.queue);
  vkFreeCommandBuffers(dev, s.pool, 1, &cmd);
  return r == VK_SUCCESS ? XR_SUCCESS : XR_ERROR_RUNTIME_FAILURE;
}

void destroy_images(Session& s, Swapchain& chain) {
  for (VkImage image : chain.images) vkDestroyImage(s.binding.device, image, nullptr);
  for (VkDeviceMemory m : chain.memory) vkFreeMemory(s.binding.device, m, nullptr);
  chain.images.clear();
  chain.memory.clear();
}

XrResult XRAPI_CALL enumerate_swapchain_formats(XrSession handle, uint32_t capacity, uint32_t* count,
                                                int64_t* formats) {
  std::lock_guard lock(runtime().mutex);
  if (!runtime().get<Session>(reinterpret_cast<std::uintptr_t>(handle), Kind::session)) return XR_ERROR_HANDLE_INVALID;
  std::vector<int64_t> all;
  for (VkFormat f : kFormats) all.push_back(f);
  return two_call(all, capacity, count, formats);
}

XrResult XRAPI_CALL create_swapchain(XrSession handle, const XrSwapchainCreateInfo* info, XrSwapchain* out) {
  std::lock_guard lock(runtime().mutex);
  Session* s = runtime().get<Session>(reinterpret_cast<std::uintptr_t>(handle), Kind::session);
  if (s == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info == nullptr || out == nullptr || info->type != XR_TYPE_SWAPCHAIN_CREATE_INFO) return XR_ERROR_VALIDATION_FAILURE;
  if (s->loss_pending) return XR_SESSION_LOSS_PENDING;
  if (std::find(std::begin(kFormats), std::end(kFormats), static_cast<VkFormat>(info->format)) == std::end(kFormats))
    return XR_ERROR_SWAPCHAIN_FORMAT_UNSUPPORTED;
  if (info->createFlags != 0 || info->faceCount != 1 || info->arraySize != 1 || info->mipCount != 1 ||
      info->sampleCount != 1)
    return XR_ERROR_FEATURE_UNSUPPORTED;
  if (info->width < 1 || info->height < 1 || info->width > 4096 || info->height > 4096) return XR_ERROR_SIZE_INSUFFICIENT;
  VkImageUsageFlags usage = 0;
  if (info->usageFlags & XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT) usage |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  if (info->usageFlags & XR_SWAPCHAIN_USAGE_TRANSFER_DST_BIT) usage |= VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  if (info->usageFlags & XR_SWAPCHAIN_USAGE_TRANSFER_SRC_BIT) usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  if (info->usageFlags & XR_SWAPCHAIN_USAGE_SAMPLED_BIT) usage |= VK_IMAGE_USAGE_SAMPLED_BIT;
  if (info->usageFlags & XR_SWAPCHAIN_USAGE_UNORDERED_ACCESS_BIT) return XR_ERROR_FEATURE_UNSUPPORTED;  // sRGB storage
  if (info->usageFlags & XR_SWAPCHAIN_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT) return XR_ERROR_FEATURE_UNSUPPORTED;
  auto chain = std::make_unique<Swapchain>();
  chain->session = s;
  chain->format = static_cast<VkFormat>(info->format);
  chain->width = info->width;
  chain->height = info->height;
  if (XrResult r = make_images(*s, *chain, usage); r != XR_SUCCESS) {
    destroy_images(*s, *chain);
    return r;
  }
  Swapchain* raw = chain.release();
  runtime().live[raw] = Kind::swapchain;
  s->swapchains.push_back(raw);
  *out = reinterpret_cast<XrSwapchain>(raw);
  return XR_SUCCESS;
}

void destroy_swapchain_locked(Swapchain* chain) {
  Session& s = *chain->session;
  destroy_images(s, *chain);
  s.swapchains.erase(std::remove(s.swapchains.begin(), s.swapchains.end(), chain), s.swapchains.end());
  runtime().live.erase(chain);
  delete chain;
}

XrResult XRAPI_CALL destroy_swapchain(XrSwapchain handle) {
  std::lock_guard lock(runtime().mutex);
  Swapchain* c = chain_of(handle);
  if (c == nullptr) return XR_ERROR_HANDLE_INVALID;
  destroy_swapchain_locked(c);
  return XR_SUCCESS;
}

XrResult XRAPI_CALL enumerate_swapchain_images(XrSwapchain handle, uint32_t capacity, uint32_t* count,
                                               XrSwapchainImageBaseHeader* images) {
  std::lock_guard lock(runtime().mutex);
  Swapchain* c = chain_of(handle);
  if (c == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (count == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  *count = static_cast<uint32_t>(c->images.size());
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < c->images.size()) return XR_ERROR_SIZE_INSUFFICIENT;
  if (images == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  auto* vk = reinterpret_cast<XrSwapchainImageVulkan2KHR*>(images);
  for (std::size_t i = 0; i < c->images.size(); ++i) {
    if (vk[i].type != XR_TYPE_SWAPCHAIN_IMAGE_VULKAN2_KHR) return XR_ERROR_VALIDATION_FAILURE;
    vk[i].image = c->images[i];
  }
  return XR_SUCCESS;
}

XrResult XRAPI_CALL acquire_swapchain_image(XrSwapchain handle, const XrSwapchainImageAcquireInfo* info,
                                            uint32_t* index) {
  std::lock_guard lock(runtime().mutex);
  Swapchain* c = chain_of(handle);
  if (c == nullptr) return XR_ERROR_HANDLE_INVALID;
  if ((info != nullptr && info->type != XR_TYPE_SWAPCHAIN_IMAGE_ACQUIRE_INFO) || index == nullptr)
    return XR_ERROR_VALIDATION_FAILURE;
  if (c->session->loss_pending) return XR_SESSION_LOSS_PENDING;
  const std::size_t held = c->acquired.size() + (c->waited ? 1 : 0);
  if (held >= c->images.size()) return XR_ERROR_CALL_ORDER_INVALID;  // every image is the app's
  *index = c->next;
  c->acquired.push_back(c->next);
  c->next = (c->next + 1) % static_cast<std::uint32_t>(c->images.size());
  return XR_SUCCESS;
}

XrResult XRAPI_CALL wait_swapchain_image(XrSwapchain handle, const XrSwapchainImageWaitInfo* info) {
  std::lock_guard lock(runtime().mutex);
  Swapchain* c = chain_of(handle);
  if (c == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info == nullptr || info->type != XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO) return XR_ERROR_VALIDATION_FAILURE;
  if (c->session->loss_pending) return XR_SESSION_LOSS_PENDING;
  if (c->acquired.empty() || c->waited) return XR_ERROR_CALL_ORDER_INVALID;
  // Nothing of the runtime's is ever in flight on an image it hands out: ready at once.
  c->waited = c->acquired.front();
  c->acquired.pop_front();
  return XR_SUCCESS;
}

XrResult XRAPI_CALL release_swapchain_image(XrSwapchain handle, const XrSwapchainImageReleaseInfo* info) {
  std::lock_guard lock(runtime().mutex);
  Swapchain* c = chain_of(handle);
  if (c == nullptr) return XR_ERROR_HANDLE_INVALID;
  if (info != nullptr && info->type != XR_TYPE_SWAPCHAIN_IMAGE_RELEASE_INFO) return XR_ERROR_VALIDATION_FAILURE;
  if (c->session->loss_pending) return XR_SESSION_LOSS_PENDING;
  if (!c->waited) return XR_ERROR_CALL_ORDER_INVALID;
  c->released = c->waited;
  c->waited.reset();
  return XR_SUCCESS;
}

}  // namespace ddish::xr_runtime
