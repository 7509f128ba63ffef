// XR_KHR_vulkan_enable2 on gpu/'s side: the hooks of gpu::ContextOptions that let the runtime
// create the Vulkan instance and device (xrCreateVulkanInstanceKHR, xrCreateVulkanDeviceKHR)
// from the create infos gpu/ builds, on the physical device the runtime names
// (xrGetVulkanGraphicsDevice2KHR). gpu/ still destroys both handles, as the binding requires.
#pragma once

#include "gpu/context.h"

namespace ddish::xr {

class Instance;

// Queries the runtime's Vulkan requirements (which the specification demands before a session)
// and sets options.create_instance, pick_physical and create_device. Throws std::runtime_error
// when the runtime cannot take Vulkan 1.3. `xr` must outlive the context made with the options.
void bind_vulkan(const Instance& xr, gpu::ContextOptions& options);

}  // namespace ddish::xr
