// `ddish render --window`: the frame loop's live view source and frame sink. The window's
// interactive camera (window/orbit_camera.h) makes each frame's views, so moving it re-ranks the
// probes like any view; after each batch the renderer's display buffer is gathered on the GPU
// (display/gpu_compositor.h) and, after the frame, composed into the display's image (single
// view, stereo pair, quilt, or with a calibration the lenticular panel image) and presented
// (gpu/presenter.h). Nothing is read back for the window.
//
// Order of life: the window opens before the GPU context (its surface extensions go into the
// instance), attach() after it, detach() (LiveAttachment) before the context goes.
#pragma once

#include <atomic>
#include <chrono>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "app/probe_source.h"
#include "display/gpu_compositor.h"
#include "display/lenticular.h"
#include "display/quilt_layout.h"
#include "raster/renderer.h"
#include "scene/scene.h"
#include "window/input.h"
#include "window/orbit_camera.h"
#include "window/sdl_window.h"

namespace ddish::gpu {
class Context;
class Presenter;
}  // namespace ddish::gpu


namespace ddish::app {

struct LiveArgs {
  bool window = false;      // --window
  int monitor = -1;         // --monitor N; -1: the monitor of the profile's panel size, else 0
  bool fullscreen = false;  // --fullscreen
  bool mailbox = false;     // --mailbox: MAILBOX where offered, else FIFO
  bool hold = false;        // --hold: after the last frame keep showing it until closed
  bool no_status = false;   // --no-status: start with the status text hidden (H toggles it)
};

// What the window says about the run: the title line, and the lines of status text drawn in
// the window's top-left corner (display/status_font.h's capitals).
struct LiveStatus {
  std::string title;
  std::vector<std::string> lines;
};

// What the keys switched since the last take_switches().
struct LiveSwitches {
  bool indirect = false;
  bool schedule = false;
  bool overlay = false;
  bool status = false;
};

class LiveWindow {
 public:
  // `start` is the scene camera the run starts from and `focal` its focal distance: the orbit
  // target is that far ahead, so the first frame equals the headless run's. Throws
  // window::WindowError (no display server, bad monitor).
  // `panel`: the display profile's panel resolution (0 × 0 without one), to find its monitor.
  LiveWindow(const LiveArgs& args, const std::string& title, int frame_width, int frame_height,
             int panel_width, int panel_height, const scene::Camera& start, float focal);
  ~LiveWindow();

  std::vector<std::string> instance_extensions() const { return window_.instance_extensions(); }
  static std::vector<std::string> device_extensions();

  // The GPU half: surface, swapchain, compositor for `views` views of layout's tiles.
  void attach(gpu::Context& gpu, const display::QuiltLayout& layout, int views,
              const std::optional<display::LenticularMapping>& lenticular);
  void detach();

  // Once per frame, before its views: events → camera, switches, resize, quit.
  void pump();
  // The camera as the user has moved it (the start camera's clip planes and fov), and the
  // focal distance (the orbit distance).
  scene::Camera camera() const;
  float focal_distance() const { return camera_.distance(); }
  window::OrbitCamera& orbit() { return camera_; }

  // The renderer's hand-off: gather each batch (read_back: also read the pixels back, for files).
  raster::RenderRequest request(bool read_back) const;
  // Composes and presents the frame gathered last; returns the milliseconds it took.
  double present();
  // Keeps presenting the last frame until the window is closed or `stop` is raised. (On a
  // lenticular panel the text is in the gathered views, so H cannot hide it from a held frame.)
  void hold(const std::atomic<bool>& stop);

  LiveSwitches take_switches();
  // The run's name in the log lines the window writes (minimised, restored): "render", "view".
  void set_tag(const char* tag) { tag_ = tag; }
  // The probe-grid overlay for the next presents (empty: none).
  void set_overlay(std::span<const display::GpuCompositor::OverlayPoint> points,
                   std::span<const glm::mat4> view_projections);
  bool quit() const { return quit_; }
  // The title now; the text from the next present on (while shown), at a scale that keeps it
  // readable: 1 up to a 1280-pixel-wide window, one more per 1280 pixels, divided by how much
  // the presenter shrinks the image to fit (an atlas) or by how much the panel enlarges a view
  // (lenticular: the text is drawn into every view).
  void set_status(const LiveStatus& status);
  bool status_shown() const { return status_shown_; }
  const window::Window& window() const { return window_; }
  int output_width() const;
  int output_height() const;

 private:
  LiveArgs args_;
  window::Window window_;
  window::OrbitCamera camera_;
  window::InputState input_;
  scene::Camera start_;
  bool quit_ = false;
  bool resized_ = false;
  LiveSwitches switches_;
  std::string tag_ = "render";
  bool status_shown_ = true;
  std::vector<std::string> status_lines_;
  std::chrono::steady_clock::time_point last_pump_;
  std::unique_ptr<display::GpuCompositor> compositor_;
  std::unique_ptr<gpu::Presenter> presenter_;
};

// The probe source with the window's indirect-light switch: while off, the frame's probe update
// is skipped (as with --no-indirect); everything else passes through.
class SwitchableProbes final : public ProbeSource {
 public:
  SwitchableProbes(ProbeSource& inner, const bool& on) : inner_(inner), on_(on) {}
  probes::ProbeVolume& volume() override { return inner_.volume(); }
  void posed(const scene::Scene& scene, const std::vector<int>& moved,
             metrics::FrameTimings& timings) override {
    inner_.posed(scene, moved, timings);
  }
  ProbeStep update(const std::vector<scene::View>& views, bool enabled,
                   metrics::FrameTimings& timings, FrameCounts& counts) override {
    return inner_.update(views, enabled && on_, timings, counts);
  }
  void finished(int frame, const metrics::FrameTimings& timings, const ProbeStep& step,
                bool enabled, FrameCounts& counts) override {
    inner_.finished(frame, timings, step, enabled && on_, counts);
  }
  void set_frame_budget(double budget_ms) override { inner_.set_frame_budget(budget_ms); }
  WarmupReport warm_up(const WarmupOptions& options) override {
    return on_ ? inner_.warm_up(options) : WarmupReport{};
  }
  std::optional<raster::GpuProbeData> gpu_probes() override { return inner_.gpu_probes(); }
  void read_back() override { inner_.read_back(); }

 private:
  ProbeSource& inner_;
  const bool& on_;
};

// The probe-grid overlay of the frame's views: every probe of `volume` as a dot, green when
// active, yellow while not yet classified, red when inactive (inside geometry); null: none.
void set_probe_overlay(LiveWindow& live, const probes::ProbeVolume* volume,
                       std::span<const scene::View> views);

// Detaches the window's GPU half when it goes: declare it after the gpu::Context.
struct LiveAttachment {
  LiveWindow* live = nullptr;
  ~LiveAttachment() {
    if (live) live->detach();
  }
};

}  // namespace ddish::app
