// The live window's camera and its SDL bindings, with the numbers window/orbit_camera.h and
// window/input.h document. Events go through SDL's own queue (SDL_PushEvent / SDL_PollEvent,
// events subsystem only: no display needed), as the window's pump reads them.
#include <cmath>

#include <SDL2/SDL.h>
#include <gtest/gtest.h>

#include "window/input.h"
#include "window/orbit_camera.h"

namespace ddish::window {
namespace {

constexpr float kFov = 0.8f;

// Eye 4 units in front of the origin (on +z), looking at it, y up: yaw 0, pitch 0, distance 4.
OrbitCamera front_camera() { return OrbitCamera({0, 0, 4}, {0, 0, 0}, {0, 1, 0}, kFov); }

TEST(OrbitCamera, StartsWhereItWasPut) {
  const OrbitCamera c = front_camera();
  EXPECT_NEAR(glm::length(c.eye() - glm::vec3(0, 0, 4)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(c.forward() - glm::vec3(0, 0, -1)), 0.0f, 1e-6f);
  EXPECT_FLOAT_EQ(c.distance(), 4.0f);
}

TEST(OrbitCamera, OrbitPanDollyFlyMoveByTheDocumentedAmounts) {
  OrbitCamera c = front_camera();
  c.orbit(100.0f, 0.0f);  // 100 px: 0.5 rad of yaw, the eye stays 4 from the target
  EXPECT_NEAR(c.yaw(), 0.5f, 1e-6f);
  EXPECT_NEAR(glm::length(c.eye() - c.target()), 4.0f, 1e-5f);
  EXPECT_NEAR(std::atan2(c.eye().x, c.eye().z), 0.5f, 1e-5f);  // turned 0.5 rad about +y
  c.orbit(0.0f, 1e6f);  // pitch clamps at 89 degrees
  EXPECT_NEAR(c.pitch(), 89.0f * 3.14159265f / 180.0f, 1e-5f);

  OrbitCamera p = front_camera();
  p.pan(0.0f, 300.0f, 300);  // a window height of drag: the view's height at the target
  EXPECT_NEAR(p.target().y, 2.0f * 4.0f * std::tan(0.5f * kFov), 1e-5f);
  EXPECT_NEAR(p.target().x, 0.0f, 1e-6f);
  p.pan(-30.0f, 0.0f, 300);  // drag left: the target moves right (+x from the front)
  EXPECT_NEAR(p.target().x, 30.0f * 2.0f * 4.0f * std::tan(0.5f * kFov) / 300.0f, 1e-5f);

  OrbitCamera d = front_camera();
  d.dolly(2.0f);
  EXPECT_NEAR(d.distance(), 4.0f * 0.81f, 1e-5f);
  d.dolly(-2.0f);
  EXPECT_NEAR(d.distance(), 4.0f, 1e-5f);

  OrbitCamera f = front_camera();
  f.fly({0, 0, 1}, 0.5f);  // forward for half a second: half a target distance
  EXPECT_NEAR(f.target().z, -2.0f, 1e-5f);
  EXPECT_NEAR(f.eye().z, 2.0f, 1e-5f);
  EXPECT_TRUE(f.take_moved());
  EXPECT_FALSE(f.take_moved());
}

TEST(OrbitCamera, DegenerateStartIsRefused) {
  EXPECT_THROW(OrbitCamera({0, 0, 0}, {0, 0, 0}, {0, 1, 0}, kFov), std::invalid_argument);
  EXPECT_THROW(OrbitCamera({0, 5, 0}, {0, 0, 0}, {0, 1, 0}, kFov), std::invalid_argument);
}

class SdlEvents : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_EQ(SDL_Init(SDL_INIT_EVENTS), 0) << SDL_GetError(); }
  void TearDown() override { SDL_Quit(); }

  static void push(SDL_Event e) { ASSERT_EQ(SDL_PushEvent(&e), 1) << SDL_GetError(); }
  static void button(Uint32 type, Uint8 which) {
    SDL_Event e{};
    e.type = type;
    e.button.button = which;
    push(e);
  }
  static void motion(int dx, int dy) {
    SDL_Event e{};
    e.type = SDL_MOUSEMOTION;
    e.motion.xrel = dx;
    e.motion.yrel = dy;
    push(e);
  }
  static void key(Uint32 type, SDL_Keycode k) {
    SDL_Event e{};
    e.type = type;
    e.key.keysym.sym = k;
    push(e);
  }
  // What the window's pump does: every queued event into the input state.
  InputActions pump(OrbitCamera& camera, int height = 300) {
    InputActions actions;
    SDL_Event e;
    while (SDL_PollEvent(&e)) input_.handle(e, camera, height, actions);
    return actions;
  }
  InputState input_;
};

TEST_F(SdlEvents, LeftDragOrbitsRightDragPansWheelDollies) {
  OrbitCamera c = front_camera();
  button(SDL_MOUSEBUTTONDOWN, SDL_BUTTON_LEFT);
  motion(40, 0);
  motion(60, 0);
  button(SDL_MOUSEBUTTONUP, SDL_BUTTON_LEFT);
  motion(500, 0);  // no button: nothing
  pump(c);
  EXPECT_NEAR(c.yaw(), 0.5f, 1e-6f);

  button(SDL_MOUSEBUTTONDOWN, SDL_BUTTON_RIGHT);
  motion(0, 150);
  button(SDL_MOUSEBUTTONUP, SDL_BUTTON_RIGHT);
  const glm::vec3 before = c.target();
  pump(c, 300);
  EXPECT_NEAR(glm::length(c.target() - before), 150.0f * 2.0f * 4.0f * std::tan(0.5f * kFov) / 300.0f, 1e-5f);

  SDL_Event wheel{};
  wheel.type = SDL_MOUSEWHEEL;
  wheel.wheel.y = 3;
  wheel.wheel.direction = SDL_MOUSEWHEEL_NORMAL;
  push(wheel);
  pump(c);
  EXPECT_NEAR(c.distance(), 4.0f * 0.729f, 1e-5f);
}

TEST_F(SdlEvents, HeldKeysFlyAndSwitchKeysToggle) {
  OrbitCamera c = front_camera();
  key(SDL_KEYDOWN, SDLK_d);  // right: +x from the front
  pump(c);
  input_.advance(c, 0.25f);
  EXPECT_NEAR(c.target().x, 1.0f, 1e-5f);  // a quarter of distance 4
  key(SDL_KEYUP, SDLK_d);
  pump(c);
  input_.advance(c, 1.0f);
  EXPECT_NEAR(c.target().x, 1.0f, 1e-5f);  // released: still

  key(SDL_KEYDOWN, SDLK_i);
  key(SDL_KEYDOWN, SDLK_u);
  InputActions a = pump(c);
  EXPECT_TRUE(a.toggle_indirect);
  EXPECT_TRUE(a.toggle_schedule);
  EXPECT_FALSE(a.toggle_overlay);
  EXPECT_FALSE(a.quit);
  key(SDL_KEYDOWN, SDLK_i);  // twice in one frame: back where it was
  key(SDL_KEYDOWN, SDLK_i);
  EXPECT_FALSE(pump(c).toggle_indirect);

  SDL_Event quit{};
  quit.type = SDL_QUIT;
  push(quit);
  EXPECT_TRUE(pump(c).quit);
  key(SDL_KEYDOWN, SDLK_ESCAPE);
  EXPECT_TRUE(pump(c).quit);
}

}  // namespace
}  // namespace ddish::window
