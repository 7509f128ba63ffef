// `--tracer auto|embree|vulkan` (render, probes, serve): which probe tracer updates the probes,
// and the in-process probe engine built for the choice. `auto` takes the Vulkan ray-tracing
// tracer (trace_vk/) only on a GPU whose driver has ray-tracing pipelines, else Embree: a CPU
// device (lavapipe) traces 22-36x slower than Embree (DESIGN.md), so there auto is always
// Embree. `vulkan` on a device without ray tracing is one error line (exit 2).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "probes/probe_tracer.h"
#include "probes/probe_updater.h"
#include "probes/tracer_source.h"
#include "raster/probe_import.h"
#include "trace/tracer.h"

namespace CLI {
class App;
}
namespace ddish::gpu {
class Context;
class Device;
}
namespace ddish::scene {
struct Scene;
}
namespace ddish::trace_vk {
class VkProbeTracer;
}

namespace ddish::app {

enum class TracerKind { embree, vulkan };

// Registers --tracer on cmd, writing into `choice` ("auto" by default).
void add_tracer_option(CLI::App& cmd, std::string& choice);
// Registers --probe-readback (render, xr): with the Vulkan tracer on the renderer's device, hand
// the probes to the rasterizer through the CPU volume as the Embree tracer does (the path without
// the GPU-resident hand-off), for comparison.
void add_probe_readback_option(CLI::App& cmd, bool& readback);

struct TracerDecision {
  TracerKind kind = TracerKind::embree;
  std::string why;  // one line for the run log and `ddish info`
};

// Decides `choice` on Vulkan device `device` (--device; default: the default device). Throws
// std::invalid_argument for `vulkan` where it cannot run.
TracerDecision choose_tracer(const std::string& choice, std::optional<std::uint32_t> device);

// What `--tracer auto` takes on the default device, for `ddish info`; never throws (no usable
// Vulkan device: Embree).
std::string auto_tracer_line();

// The in-process probe update for a decision: the Embree path tracer with probes::ProbeTracer,
// or trace_vk::VkProbeTracer on `shared` (a device opened with ray tracing that outlives the
// engine: the renderer's) or, without one, on a ray-tracing Vulkan context of its own.
class ProbeEngine {
 public:
  ProbeEngine(TracerKind kind, const scene::Scene& scene, const trace::PathOptions& path,
              const probes::UpdateOptions& options, std::optional<std::uint32_t> device,
              const gpu::Device* shared = nullptr);
  ~ProbeEngine();
  ProbeEngine(const ProbeEngine&) = delete;
  ProbeEngine& operator=(const ProbeEngine&) = delete;

  probes::ProbeUpdater& updater();
  // Follows the scene posed at a new time (the instances that moved).
  void posed(const scene::Scene& scene, std::span<const int> moved);
  TracerKind kind() const { return kind_; }

  // The GPU-resident hand-off (DESIGN.md, "GPU probe tracing"): with the Vulkan tracer on the
  // `shared` device, its averages stay there (trace_vk::VkProbeTracer::defer_host_copy) and the
  // renderer converts them itself (gpu_probes()). Returns whether it is on: never for Embree or a
  // tracer on a device of its own.
  bool keep_probes_on_device(bool on);
  // While the hand-off is on and the host volume is behind: the averages on the shared device.
  std::optional<raster::GpuProbeData> gpu_probes() const;
  // Brings the volume's coefficients and moments up to date where the hand-off left them on the
  // GPU (for the CPU's readers: a full upload, a file, the stream); nothing otherwise.
  void read_back(probes::ProbeVolume& volume);

 private:
  TracerKind kind_;
  bool on_shared_ = false;  // the Vulkan tracer runs on the caller's device
  bool on_device_ = false;  // keep_probes_on_device
  std::unique_ptr<trace::Tracer> tracer_;
  std::unique_ptr<probes::TracerSource> source_;
  std::unique_ptr<probes::ProbeTracer> cpu_;
  std::unique_ptr<gpu::Context> gpu_;
  std::unique_ptr<trace_vk::VkProbeTracer> vk_;
};

}  // namespace ddish::app
