// The live window: SDL2's video subsystem, one window with a Vulkan surface, and what Vulkan
// needs from it (instance extensions, the surface, the drawable size). The only SDL user is this
// module; the rest of ddish sees a VkSurfaceKHR and pixel sizes. Headless runs never construct
// one, so they never need a display server.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <SDL2/SDL.h>
#include <vulkan/vulkan.h>

namespace ddish::window {

// No display server, or SDL cannot make a Vulkan window on it: one line for the user.
class WindowError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct WindowOptions {
  std::string title = "ddish";
  int width = 512;   // the frame's size: the window opens this big where the monitor has room
  int height = 512;
  // SDL display index (--monitor N); -1: the monitor whose resolution is `panel_width` ×
  // `panel_height` (a Looking Glass panel), else monitor 0.
  int monitor = 0;
  int panel_width = 0;
  int panel_height = 0;
  bool fullscreen = false;  // borderless at the monitor's native mode ("fullscreen desktop")
};

// Whether the environment names a display server SDL could use (DISPLAY or WAYLAND_DISPLAY, or
// SDL_VIDEODRIVER set by the user); checked before anything else so that a headless machine gets
// its one error line before the scene is loaded.
bool display_server_named();

class Window {
 public:
  // Initialises SDL video and opens the window on the monitor, shrunk (aspect kept) to the
  // monitor's usable area when the frame is larger. Throws WindowError with SDL's reason when
  // there is no display server, the monitor does not exist, or SDL has no Vulkan support.
  explicit Window(const WindowOptions& options);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  // The instance extensions a surface on this window needs (VK_KHR_surface and the platform's).
  std::vector<std::string> instance_extensions() const;
  // Creates the surface on `instance`; the window destroys it (before the instance must go:
  // call destroy_surface() first).
  VkSurfaceKHR create_surface(VkInstance instance);
  void destroy_surface();

  VkExtent2D drawable_size() const;
  int monitor_count() const;
  // The monitor the window opened on, and every monitor as "N NAME WxH at X,Y" (the run log).
  int monitor() const { return monitor_; }
  static std::vector<std::string> monitors();
  void set_title(const std::string& title);
  SDL_Window* handle() const { return window_; }
  std::uint32_t id() const { return SDL_GetWindowID(window_); }

 private:
  SDL_Window* window_ = nullptr;
  int monitor_ = 0;
  VkInstance instance_ = VK_NULL_HANDLE;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
};

}  // namespace ddish::window
