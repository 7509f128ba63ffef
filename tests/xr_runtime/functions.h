// The OpenXR functions the test runtime implements: what `ddish xr` (src/xr/) and the core
// validation layer call, no more. xrGetInstanceProcAddr (entry.cpp) hands these out by name.
#pragma once

#include "runtime_state.h"

namespace ddish::xr_runtime {

// entry.cpp: instance, system, events
XrResult XRAPI_CALL enumerate_instance_extensions(const char* layer, uint32_t capacity,
                                                  uint32_t* count, XrExtensionProperties* props);
XrResult XRAPI_CALL create_instance(const XrInstanceCreateInfo* info, XrInstance* instance);
XrResult XRAPI_CALL destroy_instance(XrInstance instance);
XrResult XRAPI_CALL get_instance_properties(XrInstance instance, XrInstanceProperties* props);
XrResult XRAPI_CALL poll_event(XrInstance instance, XrEventDataBuffer* event);
XrResult XRAPI_CALL result_to_string(XrInstance instance, XrResult value, char* buffer);
XrResult XRAPI_CALL structure_type_to_string(XrInstance instance, XrStructureType value,
                                             char* buffer);
XrResult XRAPI_CALL get_system(XrInstance instance, const XrSystemGetInfo* info, XrSystemId* id);
XrResult XRAPI_CALL get_system_properties(XrInstance instance, XrSystemId id,
                                          XrSystemProperties* props);
XrResult XRAPI_CALL enumerate_view_configurations(XrInstance instance, XrSystemId id,
                                                  uint32_t capacity, uint32_t* count,
                                                  XrViewConfigurationType* types);
XrResult XRAPI_CALL get_view_configuration_properties(XrInstance instance, XrSystemId id,
                                                      XrViewConfigurationType type,
                                                      XrViewConfigurationProperties* props);
XrResult XRAPI_CALL enumerate_view_configuration_views(XrInstance instance, XrSystemId id,
                                                       XrViewConfigurationType type,
                                                       uint32_t capacity, uint32_t* count,
                                                       XrViewConfigurationView* views);
XrResult XRAPI_CALL enumerate_blend_modes(XrInstance instance, XrSystemId id,
                                          XrViewConfigurationType type, uint32_t capacity,
                                          uint32_t* count, XrEnvironmentBlendMode* modes);

// vulkan_binding.cpp: XR_KHR_vulkan_enable2
XrResult XRAPI_CALL get_vulkan_requirements(XrInstance instance, XrSystemId id,
                                            XrGraphicsRequirementsVulkanKHR* req);
XrResult XRAPI_CALL create_vulkan_instance(XrInstance instance,
                                           const XrVulkanInstanceCreateInfoKHR* info,
                                           VkInstance* vk_instance, VkResult* vk_result);
XrResult XRAPI_CALL create_vulkan_device(XrInstance instance,
                                         const XrVulkanDeviceCreateInfoKHR* info,
                                         VkDevice* vk_device, VkResult* vk_result);
XrResult XRAPI_CALL get_vulkan_device(XrInstance instance,
                                      const XrVulkanGraphicsDeviceGetInfoKHR* info,
                                      VkPhysicalDevice* device);

// session.cpp: session, spaces, frames, views
XrResult XRAPI_CALL create_session(XrInstance instance, const XrSessionCreateInfo* info,
                                   XrSession* session);
XrResult XRAPI_CALL destroy_session(XrSession session);
XrResult XRAPI_CALL begin_session(XrSession session, const XrSessionBeginInfo* info);
XrResult XRAPI_CALL end_session(XrSession session);
XrResult XRAPI_CALL request_exit_session(XrSession session);
XrResult XRAPI_CALL enumerate_reference_spaces(XrSession session, uint32_t capacity,
                                               uint32_t* count, XrReferenceSpaceType* spaces);
XrResult XRAPI_CALL create_reference_space(XrSession session,
                                           const XrReferenceSpaceCreateInfo* info,
                                           XrSpace* space);
XrResult XRAPI_CALL destroy_space(XrSpace space);
XrResult XRAPI_CALL wait_frame(XrSession session, const XrFrameWaitInfo* info,
                               XrFrameState* state);
XrResult XRAPI_CALL begin_frame(XrSession session, const XrFrameBeginInfo* info);
XrResult XRAPI_CALL end_frame(XrSession session, const XrFrameEndInfo* info);
XrResult XRAPI_CALL locate_views(XrSession session, const XrViewLocateInfo* info,
                                 XrViewState* state, uint32_t capacity, uint32_t* count,
                                 XrView* views);

// swapchain.cpp
XrResult XRAPI_CALL enumerate_swapchain_formats(XrSession session, uint32_t capacity,
                                                uint32_t* count, int64_t* formats);
XrResult XRAPI_CALL create_swapchain(XrSession session, const XrSwapchainCreateInfo* info,
                                     XrSwapchain* swapchain);
XrResult XRAPI_CALL destroy_swapchain(XrSwapchain swapchain);
XrResult XRAPI_CALL enumerate_swapchain_images(XrSwapchain swapchain, uint32_t capacity,
                                               uint32_t* count,
                                               XrSwapchainImageBaseHeader* images);
XrResult XRAPI_CALL acquire_swapchain_image(XrSwapchain swapchain,
                                            const XrSwapchainImageAcquireInfo* info,
                                            uint32_t* index);
XrResult XRAPI_CALL wait_swapchain_image(XrSwapchain swapchain,
                                         const XrSwapchainImageWaitInfo* info);
XrResult XRAPI_CALL release_swapchain_image(XrSwapchain swapchain,
                                            const XrSwapchainImageReleaseInfo* info);

PFN_xrGetInstanceProcAddr instance_proc_addr();

// Destroys a swapchain whose session is locked already (xrDestroySession's children).
void destroy_swapchain_locked(Swapchain* chain);

// The two-call idiom: the count, or XR_ERROR_SIZE_INSUFFICIENT when capacity is too small.
template <typename T>
XrResult two_call(const std::vector<T>& items, uint32_t capacity, uint32_t* count, T* out) {
  if (count == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  *count = static_cast<uint32_t>(items.size());
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < items.size()) return XR_ERROR_SIZE_INSUFFICIENT;
  if (out == nullptr) return XR_ERROR_VALIDATION_FAILURE;
  for (std::size_t i = 0; i < items.size(); ++i) out[i] = items[i];
  return XR_SUCCESS;
}

}  // namespace ddish::xr_runtime
