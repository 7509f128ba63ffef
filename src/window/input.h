// SDL events → the live window's camera and switches. The bindings (also in `ddish render
// --help` and the README):
//   left drag           orbit (window/orbit_camera.h has the rates)
//   right / middle drag pan (shift + left drag too)
//   wheel               dolly
//   W A S D, Q E        fly forward, left, back, right, down, up (held keys, per second)
//   I                   indirect light on / off
//   U                   probe schedule: uniform ⇄ visibility
//   G                   probe-grid overlay on / off
//   H                   status text in the window shown / hidden
//   Esc, window close   quit
#pragma once

#include <SDL2/SDL.h>

#include "window/orbit_camera.h"

namespace ddish::window {

// What the events of one frame asked for, besides moving the camera.
struct InputActions {
  bool quit = false;
  bool toggle_indirect = false;
  bool toggle_schedule = false;
  bool toggle_overlay = false;
  bool toggle_status = false;
  bool resized = false;    // the drawable size changed (or the window was restored)
  bool minimised = false;  // now minimised; restored clears it
};

class InputState {
 public:
  // Applies one event to the camera (window_height: pixels, for panning) and the actions.
  void handle(const SDL_Event& event, OrbitCamera& camera, int window_height, InputActions& actions);
  // Flies for `seconds` with the keys held now.
  void advance(OrbitCamera& camera, float seconds) const;
  bool minimised() const { return minimised_; }

 private:
  enum Drag { none, orbiting, panning };
  Drag drag_ = none;
  bool minimised_ = false;
  // Held fly keys: +x D, −x A, +y E, −y Q, +z W, −z S.
  bool d_ = false, a_ = false, e_ = false, q_ = false, w_ = false, s_ = false;
};

}  // namespace ddish::window
