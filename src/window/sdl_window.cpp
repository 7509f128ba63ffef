#include "window/sdl_window.h"

#include <algorithm>
#include <cstdlib>

#include <SDL2/SDL_vulkan.h>

namespace ddish::window {

bool display_server_named() {
  for (const char* name : {"DISPLAY", "WAYLAND_DISPLAY", "SDL_VIDEODRIVER"}) {
    const char* v = std::getenv(name);
    if (v && *v) return true;
  }
  return false;
}

Window::Window(const WindowOptions& o) {
  if (!display_server_named())
    throw WindowError("--window needs a display server, and neither DISPLAY nor WAYLAND_DISPLAY "
                      "is set; without --window ddish renders to files");
  // SIGINT and SIGTERM stay ddish's (app/interrupt.h: the frame in progress ends the run).
  SDL_SetHint(SDL_HINT_NO_SIGNAL_HANDLERS, "1");
  if (SDL_InitSubSystem(SDL_INIT_VIDEO) != 0)
    throw WindowError(std::string("--window needs a display server, and SDL found none (") +
                      SDL_GetError() + "); without --window ddish renders to files");
  try {
    const int monitors = SDL_GetNumVideoDisplays();
    monitor_ = o.monitor < 0 ? 0 : o.monitor;
    if (o.monitor < 0)
      for (int m = 0; m < monitors; ++m) {
        SDL_Rect b{};
        if (SDL_GetDisplayBounds(m, &b) == 0 && b.w == o.panel_width && b.h == o.panel_height) {
          monitor_ = m;
          break;
        }
      }
    if (monitor_ >= monitors)
      throw WindowError("--monitor " + std::to_string(monitor_) + ": the display server has " +
                        std::to_string(monitors) + " monitor" + (monitors == 1 ? "" : "s") +
                        " (0.." + std::to_string(monitors - 1) + ")");
    SDL_Rect usable{};
    if (SDL_GetDisplayUsableBounds(monitor_, &usable) != 0) SDL_GetDisplayBounds(monitor_, &usable);
    int w = o.width, h = o.height;
    if (!o.fullscreen && usable.w > 0 && usable.h > 0 && (w > usable.w || h > usable.h)) {
      const double s = std::min(double(usable.w) / w, double(usable.h) / h);
      w = std::max(1, int(w * s));
      h = std::max(1, int(h * s));
    }
    Uint32 flags = SDL_WINDOW_VULKAN | SDL_WINDOW_RESIZABLE | SDL_WINDOW_ALLOW_HIGHDPI;
    if (o.fullscreen) flags |= SDL_WINDOW_FULLSCREEN_DESKTOP;
    window_ = SDL_CreateWindow(o.title.c_str(), int(SDL_WINDOWPOS_CENTERED_DISPLAY(monitor_)),
                               int(SDL_WINDOWPOS_CENTERED_DISPLAY(monitor_)), w, h, flags);
    if (!window_)
      throw WindowError(std::string("cannot open a Vulkan window: ") + SDL_GetError());
  } catch (...) {
    SDL_QuitSubSystem(SDL_INIT_VIDEO);
    throw;
  }
}

Window::~Window() {
  destroy_surface();
  if (window_) SDL_DestroyWindow(window_);
  SDL_QuitSubSystem(SDL_INIT_VIDEO);
}

std::vector<std::string> Window::instance_extensions() const {
  unsigned count = 0;
  if (!SDL_Vulkan_GetInstanceExtensions(window_, &count, nullptr))
    throw WindowError(std::string("SDL cannot name the Vulkan surface extensions: ") + SDL_GetError());
  std::vector<const char*> names(count);
  SDL_Vulkan_GetInstanceExtensions(window_, &count, names.data());
  return std::vector<std::string>(names.begin(), names.end());
}

VkSurfaceKHR Window::create_surface(VkInstance instance) {
  destroy_surface();
  if (!SDL_Vulkan_CreateSurface(window_, instance, &surface_))
    throw WindowError(std::string("cannot make a Vulkan surface on the window: ") + SDL_GetError());
  instance_ = instance;
  return surface_;
}

void Window::destroy_surface() {
  if (surface_ != VK_NULL_HANDLE) vkDestroySurfaceKHR(instance_, surface_, nullptr);
  surface_ = VK_NULL_HANDLE;
}

VkExtent2D Window::drawable_size() const {
  int w = 0, h = 0;
  SDL_Vulkan_GetDrawableSize(window_, &w, &h);
  return {std::uint32_t(std::max(0, w)), std::uint32_t(std::max(0, h))};
}

int Window::monitor_count() const { return SDL_GetNumVideoDisplays(); }

std::vector<std::string> Window::monitors() {
  std::vector<std::string> lines;
  for (int m = 0; m < SDL_GetNumVideoDisplays(); ++m) {
    SDL_Rect b{};
    SDL_GetDisplayBounds(m, &b);
    const char* name = SDL_GetDisplayName(m);
    lines.push_back(std::to_string(m) + " " + (name ? name : "?") + " " + std::to_string(b.w) + "x" +
                    std::to_string(b.h) + " at " + std::to_string(b.x) + "," + std::to_string(b.y));
  }
  return lines;
}

void Window::set_title(const std::string& title) { SDL_SetWindowTitle(window_, title.c_str()); }

}  // namespace ddish::window
