#include "app/live_window.h"

#include <algorithm>
#include <cstdio>
#include <thread>
#include <utility>

#include "app/interrupt.h"
#include "display/gpu_compositor.h"
#include "gpu/context.h"
#include "gpu/presenter.h"
#include "metrics/color.h"
#include "probes/probe_volume.h"

namespace ddish::app {

namespace {

std::vector<float> decoded_srgb8() {
  std::vector<float> t(256);
  for (int c = 0; c < 256; ++c) t[std::size_t(c)] = metrics::srgb8_decode(std::uint8_t(c));
  return t;
}

}  // namespace

LiveWindow::LiveWindow(const LiveArgs& args, const std::string& title, int frame_width,
                       int frame_height, int panel_width, int panel_height,
                       const scene::Camera& start, float focal)
    : args_(args),
      window_(window::WindowOptions{.title = title,
                                    .width = frame_width,
                                    .height = frame_height,
                                    .monitor = args.monitor,
                                    .panel_width = panel_width,
                                    .panel_height = panel_height,
                                    .fullscreen = args.fullscreen}),
      camera_(start.eye, start.eye + glm::normalize(start.forward) * focal, start.up, start.yfov),
      start_(start),
      status_shown_(!args.no_status),
      last_pump_(std::chrono::steady_clock::now()) {}

LiveWindow::~LiveWindow() { detach(); }

std::vector<std::string> LiveWindow::device_extensions() { return {VK_KHR_SWAPCHAIN_EXTENSION_NAME}; }

void LiveWindow::attach(gpu::Context& gpu, const display::QuiltLayout& layout, int views,
                        const std::optional<display::LenticularMapping>& lenticular) {
  static const std::vector<float> decoded = decoded_srgb8();
  compositor_ = std::make_unique<display::GpuCompositor>(
      gpu.device(), layout, views, lenticular,
      display::Srgb8Tables{std::span<const float, 256>(decoded.data(), 256),
                           metrics::srgb8_midpoints()});
  const VkSurfaceKHR surface = window_.create_surface(gpu.instance().handle());
  presenter_ = std::make_unique<gpu::Presenter>(gpu.device(), surface, window_.drawable_size(),
                                                args_.mailbox);
}

void LiveWindow::detach() {
  presenter_.reset();
  compositor_.reset();
  window_.destroy_surface();
}

int LiveWindow::output_width() const { return compositor_ ? compositor_->output_width() : 0; }
int LiveWindow::output_height() const { return compositor_ ? compositor_->output_height() : 0; }

void LiveWindow::pump() {
  const auto now = std::chrono::steady_clock::now();
  const float seconds = std::chrono::duration<float>(now - last_pump_).count();
  last_pump_ = now;
  window::InputActions actions;
  const int height = int(window_.drawable_size().height);
  SDL_Event ev;
  while (SDL_PollEvent(&ev)) input_.handle(ev, camera_, height, actions);
  // Minimised: nothing to show, so the loop waits here (no frames drawn, nothing presented)
  // until restored, and goes on from where it was.
  if (input_.minimised() && !actions.quit && !stop_flag().load()) {
    std::fprintf(stderr, "%s: window minimised: no frames until it is restored\n", tag_.c_str());
    const auto since = std::chrono::steady_clock::now();
    while (input_.minimised() && !actions.quit && !stop_flag().load()) {
      if (SDL_WaitEventTimeout(&ev, 100)) input_.handle(ev, camera_, height, actions);
    }
    const auto until = std::chrono::steady_clock::now();
    std::fprintf(stderr, "%s: window %s after %.0f ms minimised\n", tag_.c_str(),
                 input_.minimised() ? "closing" : "restored",
                 std::chrono::duration<double, std::milli>(until - since).count());
    last_pump_ = until;  // the fly keys do not count the time away
  }
  input_.advance(camera_, seconds);
  quit_ = quit_ || actions.quit;
  switches_.indirect = switches_.indirect != actions.toggle_indirect;
  switches_.schedule = switches_.schedule != actions.toggle_schedule;
  switches_.overlay = switches_.overlay != actions.toggle_overlay;
  switches_.status = switches_.status != actions.toggle_status;
  if (actions.toggle_status) status_shown_ = !status_shown_;
  if (actions.resized && presenter_) presenter_->resize(window_.drawable_size());
}

void LiveWindow::set_overlay(std::span<const display::GpuCompositor::OverlayPoint> points,
                             std::span<const glm::mat4> view_projections) {
  compositor_->set_overlay(points, view_projections);
}

void set_probe_overlay(LiveWindow& live, const probes::ProbeVolume* volume,
                       std::span<const scene::View> views) {
  if (!volume) {
    live.set_overlay({}, {});
    return;
  }
  std::vector<display::GpuCompositor::OverlayPoint> points;
  points.reserve(volume->probe_count());
  for (std::uint32_t i = 0; i < volume->probe_count(); ++i) {
    const probes::ProbeState& s = volume->state(i);
    // Packed RGBA8, R in the low byte.
    const std::uint32_t colour = s.unclassified() ? 0xFF00FFFFu : s.active() ? 0xFF00FF00u : 0xFF0000FFu;
    points.push_back({volume->grid().position(i), colour});
  }
  std::vector<glm::mat4> matrices;
  for (const scene::View& v : views) matrices.push_back(v.projection * v.view);
  live.set_overlay(points, matrices);
}

void LiveWindow::set_status(const LiveStatus& status) {
  window_.set_title(status.title);
  status_lines_ = status.lines;
}

namespace {

// The text scale for an image of out_w × out_h shown in a drawable of draw_w × draw_h
// (LiveWindow::set_status); `view_w`: the width the text is drawn at, when it is not the image's.
int text_scale(int draw_w, int draw_h, int out_w, int out_h, int view_w) {
  const int base = std::max(1, draw_w / 1280);
  if (view_w > 0) return std::max(1, base * view_w / std::max(1, out_w));
  const gpu::PresentPlacement at = gpu::place_frame(std::uint32_t(out_w), std::uint32_t(out_h),
                                                    std::uint32_t(std::max(1, draw_w)),
                                                    std::uint32_t(std::max(1, draw_h)));
  // Shrunk to at.width of out_w: each text pixel must cover `base` drawable pixels still.
  return std::max(1, (base * out_w + int(at.width) - 1) / std::max(1, int(at.width)));
}

}  // namespace

LiveSwitches LiveWindow::take_switches() { return std::exchange(switches_, LiveSwitches{}); }

scene::Camera LiveWindow::camera() const {
  scene::Camera c = start_;
  c.node = -1;  // the user's camera, not the animated node's
  c.eye = camera_.eye();
  c.forward = camera_.forward();
  c.up = camera_.up();
  return c;
}

raster::RenderRequest LiveWindow::request(bool read_back) const {
  raster::RenderRequest r;
  r.read_back = read_back;
  display::GpuCompositor* comp = compositor_.get();
  r.after_batch = [comp](VkCommandBuffer cmd, const raster::BatchViews& b) {
    comp->record_gather(cmd, b.display, b.first_view, b.count, b.width, b.height);
  };
  return r;
}

double LiveWindow::present() {
  const auto t0 = std::chrono::steady_clock::now();
  display::GpuCompositor& comp = *compositor_;
  if (status_shown_ && !status_lines_.empty()) {
    const VkExtent2D d = window_.drawable_size();
    comp.set_status(status_lines_, text_scale(int(d.width), int(d.height), comp.output_width(),
                                              comp.output_height(),
                                              comp.lenticular() ? comp.layout().tile_width : 0));
  } else {
    comp.set_status({}, 1);
  }
  presenter_->present(comp.output(), std::uint32_t(comp.output_width()),
                      std::uint32_t(comp.output_height()),
                      [&](VkCommandBuffer cmd) { comp.record_compose(cmd); });
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

void LiveWindow::hold(const std::atomic<bool>& stop) {
  while (!quit_ && !stop.load()) {
    pump();
    if (quit_) break;
    present();
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
  }
}

}  // namespace ddish::app
