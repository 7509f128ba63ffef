#include "window/input.h"

namespace ddish::window {

void InputState::handle(const SDL_Event& ev, OrbitCamera& camera, int window_height,
                        InputActions& actions) {
  switch (ev.type) {
    case SDL_QUIT:
      actions.quit = true;
      break;
    case SDL_WINDOWEVENT:
      switch (ev.window.event) {
        case SDL_WINDOWEVENT_CLOSE:
          actions.quit = true;
          break;
        case SDL_WINDOWEVENT_SIZE_CHANGED:
        case SDL_WINDOWEVENT_RESIZED:
          actions.resized = true;
          break;
        case SDL_WINDOWEVENT_MINIMIZED:
          minimised_ = true;
          break;
        case SDL_WINDOWEVENT_RESTORED:
        case SDL_WINDOWEVENT_SHOWN:
          if (minimised_) actions.resized = true;
          minimised_ = false;
          break;
        default:
          break;
      }
      break;
    case SDL_MOUSEBUTTONDOWN:
      if (ev.button.button == SDL_BUTTON_LEFT)
        drag_ = (SDL_GetModState() & KMOD_SHIFT) ? panning : orbiting;
      else if (ev.button.button == SDL_BUTTON_RIGHT || ev.button.button == SDL_BUTTON_MIDDLE)
        drag_ = panning;
      break;
    case SDL_MOUSEBUTTONUP:
      drag_ = none;
      break;
    case SDL_MOUSEMOTION:
      if (drag_ == orbiting)
        camera.orbit(float(ev.motion.xrel), float(ev.motion.yrel));
      else if (drag_ == panning)
        camera.pan(float(ev.motion.xrel), float(ev.motion.yrel), window_height);
      break;
    case SDL_MOUSEWHEEL: {
      const float steps = ev.wheel.direction == SDL_MOUSEWHEEL_FLIPPED ? -float(ev.wheel.y) : float(ev.wheel.y);
      camera.dolly(steps);
      break;
    }
    case SDL_KEYDOWN:
    case SDL_KEYUP: {
      const bool down = ev.type == SDL_KEYDOWN;
      switch (ev.key.keysym.sym) {
        case SDLK_w: w_ = down; break;
        case SDLK_s: s_ = down; break;
        case SDLK_a: a_ = down; break;
        case SDLK_d: d_ = down; break;
        case SDLK_q: q_ = down; break;
        case SDLK_e: e_ = down; break;
        case SDLK_ESCAPE: if (down) actions.quit = true; break;
        case SDLK_i: if (down && !ev.key.repeat) actions.toggle_indirect = !actions.toggle_indirect; break;
        case SDLK_u: if (down && !ev.key.repeat) actions.toggle_schedule = !actions.toggle_schedule; break;
        case SDLK_g: if (down && !ev.key.repeat) actions.toggle_overlay = !actions.toggle_overlay; break;
        case SDLK_h: if (down && !ev.key.repeat) actions.toggle_status = !actions.toggle_status; break;
        default: break;
      }
      break;
    }
    default:
      break;
  }
  actions.minimised = minimised_;
}

void InputState::advance(OrbitCamera& camera, float seconds) const {
  const glm::vec3 d(float(d_) - float(a_), float(e_) - float(q_), float(w_) - float(s_));
  camera.fly(d, seconds);
}

}  // namespace ddish::window
