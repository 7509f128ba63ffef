// The test runtime's objects and the one lock around them. Handles are pointers to these
// objects, known to be live only while they are in the registry: a handle that is not there
// (never made, destroyed, or of another type) is XR_ERROR_HANDLE_INVALID. Every entry point
// takes the lock, so the app may call from any thread.
#pragma once

#include <cstdint>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include <vulkan/vulkan.h>
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

#include "pose_path.h"

namespace ddish::xr_runtime {

inline constexpr XrSystemId kSystemId = 1;
inline constexpr std::uint32_t kSwapchainLength = 3;

struct Session;

struct Instance {
  bool vulkan_enable2 = false;  // XR_KHR_vulkan_enable2 was enabled
  bool requirements_queried = false;
  VkPhysicalDevice named_device = VK_NULL_HANDLE;  // what xrGetVulkanGraphicsDevice2KHR said
  Script script;
  std::filesystem::path out;  // DDISH_XR_OUT, empty: nothing written
  std::deque<XrEventDataBuffer> events;
  Session* session = nullptr;  // at most one at a time
};

struct Swapchain {
  Session* session = nullptr;
  VkFormat format = VK_FORMAT_UNDEFINED;
  std::uint32_t width = 0, height = 0;
  std::vector<VkImage> images;
  std::vector<VkDeviceMemory> memory;
  std::deque<std::uint32_t> acquired;  // acquired, not yet waited, oldest first
  std::optional<std::uint32_t> waited;  // waited, not yet released
  std::uint32_t next = 0;               // the next image to acquire
  std::optional<std::uint32_t> released;  // the image of the last release: what a layer shows
};

struct Space {
  Session* session = nullptr;
  XrReferenceSpaceType type = XR_REFERENCE_SPACE_TYPE_LOCAL;
  XrPosef pose{{0.0f, 0.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 0.0f}};  // in the LOCAL space
};

// One frame as the runtime saw it, for the record (recorder.h).
struct ViewRecord {
  XrPosef pose{};
  XrFovf fov{};
};
struct FrameRecord {
  int index = 0;
  XrTime predicted_display_time = 0;
  XrDuration predicted_display_period = 0;
  bool should_render = false;
  XrTime wait_return = 0, begin = 0, end = 0;  // runtime clock, ns
  bool ended = false;
  bool discarded = false;
  std::vector<ViewRecord> located;    // the last xrLocateViews at this frame's display time
  std::vector<ViewRecord> submitted;  // the projection layer's views; empty: no layer
  std::vector<std::string> images;    // EXR files of the submitted views
  XrTime located_at = 0;              // when xrLocateViews was called
};

struct Session {
  Instance* instance = nullptr;
  XrGraphicsBindingVulkan2KHR binding{};
  VkQueue queue = VK_NULL_HANDLE;
  VkCommandPool pool = VK_NULL_HANDLE;
  XrSessionState state = XR_SESSION_STATE_UNKNOWN;
  bool running = false;
  bool exit_requested = false;
  bool loss_pending = false;
  int frames_waited = 0;  // xrWaitFrame calls: the index of the next frame
  std::optional<int> waited;  // waited, not yet begun
  std::optional<int> begun;   // begun, not yet ended
  XrTime last_display = 0;
  std::vector<FrameRecord> frames;
  std::vector<std::string> states;  // every state the session went through, in order
  std::vector<Swapchain*> swapchains;
  std::vector<Space*> spaces;
};

enum class Kind { instance, session, swapchain, space };

struct Runtime {
  std::mutex mutex;
  std::unordered_map<const void*, Kind> live;

  template <typename T>
  T* get(std::uint64_t handle, Kind kind) {
    const void* p = reinterpret_cast<const void*>(static_cast<std::uintptr_t>(handle));
    const auto it = live.find(p);
    return it != live.end() && it->second == kind ? static_cast<T*>(const_cast<void*>(p)) : nullptr;
  }
};

Runtime& runtime();

// Nanoseconds of CLOCK_MONOTONIC: the runtime's XrTime.
XrTime now_ns();

// Queues a session state change event and makes it the session's state.
void change_state(Session& s, XrSessionState state);

// Writes the session's record (recorder.cpp); a failure is reported on stderr.
void write_record(const Session& s);

// Copies view `image` of `chain` to host memory through the session's queue and writes it as a
// linear EXR (the sRGB-encoded bytes decoded). Returns the file name, or "" when it failed
// (said on stderr).
std::string record_image(Session& s, Swapchain& chain, std::uint32_t image, const XrRect2Di& rect,
                         const std::filesystem::path& file);

// Swapchain images made and destroyed on the session's device (swapchain.cpp).
XrResult make_images(Session& s, Swapchain& chain, VkImageUsageFlags usage);
void destroy_images(Session& s, Swapchain& chain);

}  // namespace ddish::xr_runtime
