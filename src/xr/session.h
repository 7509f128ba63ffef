// The OpenXR session on gpu/'s device: the Vulkan binding, a LOCAL reference space, one
// swapchain per eye at the runtime's recommended size, and the session state machine driven by
// xrPollEvent:
//   IDLE -> READY: xrBeginSession (PRIMARY_STEREO); SYNCHRONIZED / VISIBLE / FOCUSED: frames
//   (rendered only when xrWaitFrame says shouldRender); STOPPING: xrEndSession; EXITING: over;
//   LOSS_PENDING: over, lost (the runtime or the headset is gone; the caller destroys all).
// The frame: begin_frame() is xrWaitFrame -> xrBeginFrame -> xrLocateViews at the predicted
// display time; end_frame() is xrEndFrame with a projection layer of the located views (or no
// layer when the frame was not rendered).
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <openxr/openxr.h>

#include "xr/swapchain.h"

namespace ddish::gpu {
class Device;
}

namespace ddish::xr {

class Instance;

struct Frame {
  XrTime display_time = 0;
  XrDuration display_period = 0;  // ns
  bool should_render = false;
  std::array<XrView, 2> views{};  // in LOCAL, at display_time (when should_render)
  std::chrono::steady_clock::time_point waited;   // xrWaitFrame returned
  std::chrono::steady_clock::time_point located;  // xrLocateViews returned
  double wait_ms = 0.0;                           // xrWaitFrame blocked this long
};

class Session {
 public:
  // Throws XrError / std::runtime_error with one line.
  Session(const Instance& instance, const gpu::Device& device);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  // Reads every queued event and follows the state machine.
  void poll_events();
  bool running() const { return running_; }  // between xrBeginSession and xrEndSession
  bool over() const { return over_; }        // EXITING or LOSS_PENDING (or the instance lost)
  bool lost() const { return lost_; }
  bool exit_requested() const { return exit_requested_; }
  // The states the session went through, in order ("READY", "FOCUSED", ...), for the run log.
  const std::vector<std::string>& states() const { return states_; }

  // Only while running. A LOSS_PENDING answer ends the session (over(), lost()).
  Frame begin_frame();
  void end_frame(const Frame& frame, bool with_layer);
  // The app's wish to end (xrRequestExitSession): the runtime answers with STOPPING.
  void request_exit();

  EyeSwapchain& eye(int e) { return *eyes_[static_cast<std::size_t>(e)]; }
  XrSession handle() const { return session_; }
  XrSpace local_space() const { return local_; }

 private:
  void state_changed(XrSessionState state);
  void lose();

  const Instance& instance_;
  XrSession session_ = XR_NULL_HANDLE;
  XrSpace local_ = XR_NULL_HANDLE;
  std::array<std::unique_ptr<EyeSwapchain>, 2> eyes_;
  bool running_ = false;
  bool over_ = false;
  bool lost_ = false;
  bool exit_requested_ = false;
  std::vector<std::string> states_;
};

}  // namespace ddish::xr
