// The window's Vulkan path in-process under a private Xvfb, with the validation layer and its
// synchronization checks on: SDL window → surface → swapchain → presents → resize → presents →
// destroy, and zero validation messages counted (errors, including leaks at destruction). The
// frame is a GPU buffer of packed RGBA8; where it lands follows place_frame's numbers.
#include <memory>
#include <vector>

#include <SDL2/SDL.h>
#include <gtest/gtest.h>

#include "../gpu/gpu_test.h"
#include "gpu/buffer.h"
#include "gpu/context.h"
#include "gpu/presenter.h"
#include "window/sdl_window.h"
#include "xvfb.h"

namespace ddish::window {
namespace {

TEST(PlaceFrame, OneToOneWhenItFitsElseShrunkAspectKept) {
  const gpu::PresentPlacement a = gpu::place_frame(100, 50, 200, 100);
  EXPECT_EQ(a.x, 50);
  EXPECT_EQ(a.y, 25);
  EXPECT_EQ(a.width, 100u);
  EXPECT_FALSE(a.scaled);
  const gpu::PresentPlacement b = gpu::place_frame(3360, 3360, 1920, 1080);  // a quilt on a monitor
  EXPECT_EQ(b.width, 1080u);
  EXPECT_EQ(b.height, 1080u);
  EXPECT_EQ(b.x, 420);
  EXPECT_TRUE(b.scaled);
  const gpu::PresentPlacement c = gpu::place_frame(1536, 2048, 1536, 1024);  // panel image, short window
  EXPECT_EQ(c.width, 768u);
  EXPECT_EQ(c.height, 1024u);
}

class ScopedDisplay {
 public:
  explicit ScopedDisplay(const std::string& d) : env_("DISPLAY", d) {}

 private:
  gpu::test::ScopedEnv env_;
};

TEST(WindowSwapchain, CreateResizeDestroyIsValidationClean) {
  window_test::Xvfb x(320, 240);
  ASSERT_TRUE(x.running()) << "Xvfb did not start";
  ScopedDisplay display(x.display());
  std::shared_ptr<const gpu::ValidationLog> log;
  {
    Window w(WindowOptions{.title = "swapchain test", .width = 160, .height = 120});
    gpu::ContextOptions o = gpu::test::validated_options();
    o.instance_extensions = w.instance_extensions();
    o.device_extensions = {VK_KHR_SWAPCHAIN_EXTENSION_NAME};
    auto gpu = std::make_unique<gpu::Context>(o);
    log = gpu->instance().shared_validation();
    {
      const VkSurfaceKHR surface = w.create_surface(gpu->instance().handle());
      gpu::Presenter presenter(gpu->device(), surface, w.drawable_size(), /*mailbox=*/true);
      EXPECT_EQ(presenter.swapchain().extent().width, 160u);
      EXPECT_EQ(presenter.swapchain().extent().height, 120u);
      gpu::Buffer frame(gpu->device(), 100 * 80 * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                        gpu::MemoryUse::upload);
      std::vector<std::uint32_t> px(100 * 80, 0xFF2040C0u);
      frame.write(px.data(), px.size() * 4);
      for (int i = 0; i < 3; ++i)
        EXPECT_EQ(presenter.present(frame, 100, 80), gpu::PresentStatus::presented);
      EXPECT_EQ(presenter.last_placement().x, 30);  // centred 1:1 in 160 x 120
      EXPECT_EQ(presenter.last_placement().y, 20);

      SDL_SetWindowSize(w.handle(), 64, 48);  // smaller than the frame: shrunk to fit
      for (int i = 0; i < 20 && w.drawable_size().width != 64; ++i) {
        SDL_PumpEvents();
        SDL_Delay(10);
      }
      ASSERT_EQ(w.drawable_size().width, 64u);
      presenter.resize(w.drawable_size());
      int shown = 0;
      for (int i = 0; i < 4; ++i) shown += presenter.present(frame, 100, 80) == gpu::PresentStatus::presented;
      EXPECT_GE(shown, 3);
      EXPECT_EQ(presenter.swapchain().extent().width, 64u);
      EXPECT_EQ(presenter.last_placement().width, 60u);  // 100 x 80 into 64 x 48: 60 x 48
      EXPECT_EQ(presenter.last_placement().height, 48u);
      EXPECT_TRUE(presenter.last_placement().scaled);
    }
    w.destroy_surface();
    gpu.reset();  // device and instance destruction report leaks into the log
  }
  ASSERT_TRUE(log);
  EXPECT_EQ(log->errors(), 0u) << gpu::test::describe_errors(*log);
  EXPECT_EQ(log->warnings(), 0u);
}

}  // namespace
}  // namespace ddish::window
