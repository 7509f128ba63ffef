#include "app/tracer_choice.h"

#include <stdexcept>

#include <CLI/CLI.hpp>

#include "gpu/context.h"
#include "gpu/device_info.h"
#include "gpu/instance.h"
#include "scene/scene.h"
#include "trace_vk/vk_probe_tracer.h"

namespace ddish::app {

void add_tracer_option(CLI::App& cmd, std::string& choice) {
  cmd.add_option("--tracer", choice,
                 "probe tracer: auto (Vulkan ray tracing on a GPU that has it, else Embree), embree (CPU), "
                 "vulkan (ray-tracing pipelines; on lavapipe too, slowly)")
      ->check(CLI::IsMember({"auto", "embree", "vulkan"}))
      ->capture_default_str();
}

void add_probe_readback_option(CLI::App& cmd, bool& readback) {
  cmd.add_flag("--probe-readback", readback,
               "with --tracer vulkan: copy the traced probes back to the CPU every update and upload them "
               "from there, instead of converting them on the GPU for the rasterizer (for comparison)");
}

TracerDecision choose_tracer(const std::string& choice, std::optional<std::uint32_t> device) {
  if (choice == "embree") return {TracerKind::embree, "embree (--tracer embree)"};
  // Only the device's description is needed: no device is opened here.
  const gpu::Instance instance;
  const std::vector<gpu::DeviceInfo> devices = gpu::enumerate_devices(instance);
  const gpu::DeviceInfo& info = devices[gpu::select_device(devices, device)];
  if (choice == "vulkan") {
    if (!info.ray_tracing)
      throw std::invalid_argument("--tracer vulkan: " + info.name + " (" + info.driver_info +
                                  ") has no Vulkan ray-tracing pipelines (VK_KHR_ray_tracing_pipeline, "
                                  "VK_KHR_acceleration_structure)");
    return {TracerKind::vulkan, "vulkan on " + info.name + " (--tracer vulkan)"};
  }
  if (!info.ray_tracing) return {TracerKind::embree, "embree (auto: " + info.name + " has no ray-tracing pipelines)"};
  if (info.type == gpu::DeviceType::cpu)
    return {TracerKind::embree, "embree (auto: " + info.name + " is a CPU device; Embree is faster there)"};
  return {TracerKind::vulkan, "vulkan on " + info.name + " (auto)"};
}

std::string auto_tracer_line() {
  try {
    return choose_tracer("auto", std::nullopt).why;
  } catch (const std::exception& e) {
    return std::string("embree (auto: no usable Vulkan device: ") + e.what() + ")";
  }
}

ProbeEngine::ProbeEngine(TracerKind kind, const scene::Scene& scene, const trace::PathOptions& path,
                         const probes::UpdateOptions& options, std::optional<std::uint32_t> device,
                         const gpu::Device* shared)
    : kind_(kind) {
  if (kind == TracerKind::embree) {
    tracer_ = std::make_unique<trace::Tracer>(scene, path);
    source_ = std::make_unique<probes::TracerSource>(*tracer_);
    cpu_ = std::make_unique<probes::ProbeTracer>(*source_, options);
  } else {
    on_shared_ = shared != nullptr;
    if (!shared) {
      gpu_ = std::make_unique<gpu::Context>(gpu::ContextOptions{.device_index = device, .ray_tracing = true});
      shared = &gpu_->device();
    }
    vk_ = std::make_unique<trace_vk::VkProbeTracer>(*shared, scene, path, options);
  }
}

ProbeEngine::~ProbeEngine() = default;

probes::ProbeUpdater& ProbeEngine::updater() {
  if (cpu_) return *cpu_;
  return *vk_;
}

bool ProbeEngine::keep_probes_on_device(bool on) {
  on_device_ = on && vk_ && on_shared_;
  if (vk_) vk_->defer_host_copy(on_device_);
  return on_device_;
}

std::optional<raster::GpuProbeData> ProbeEngine::gpu_probes() const {
  // Nothing stale: the host volume holds the values (and before the first update the tracer
  // has no buffers).
  if (!on_device_ || vk_->stale_probes() == 0) return std::nullopt;
  return raster::GpuProbeData{&vk_->coefficient_buffer(), &vk_->moment_buffer()};
}

void ProbeEngine::read_back(probes::ProbeVolume& volume) {
  if (vk_) vk_->read_back(volume);
}

void ProbeEngine::posed(const scene::Scene& scene, std::span<const int> moved) {
  if (tracer_) tracer_->update(scene, moved);
  if (vk_) vk_->scene_posed(scene, moved);
}

}  // namespace ddish::app
