// The probe update on Vulkan ray-tracing pipelines (DESIGN.md, "GPU probe tracing"): the same
// probes, lattice directions and random rotations as probes::ProbeTracer (the rotation of probe
// p in update k comes from the same trace::Sampler stream), the same integrator as
// trace::Tracer (shaders/probe_trace.rgen), and the SH projection, the distance moments
// (probes::MomentEstimate's rules, from the same paths' first hits), classification and running
// averages on the GPU (shaders/probe_project.comp). Probes trace from ProbeVolume::position, and
// with UpdateOptions::relocate a probe being classified first looks around once (a pass that
// blends nothing), moves by probes::relocated_offset, then updates from there, as ProbeTracer
// does. The volume's coefficients and moments live in GPU buffers (coefficient_buffer()) that the
// update blends into; the host volume gets a copy of the updated probes after each update, for
// the CPU consumers (network stream, files, the rasterizer's upload today).
//
// One path per launch item: x = the lattice direction, y = the probe. Paths draw their random
// numbers from a per-path PCG stream (not the CPU's per-probe stream), so the GPU's probes
// equal the CPU's in expectation, not bit for bit; tests/trace_vk compares them statistically.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "gpu/buffer.h"
#include "probes/probe_tracer.h"
#include "probes/probe_updater.h"
#include "trace/tracer.h"  // PathOptions

namespace ddish::gpu {
class Device;
}
namespace ddish::scene {
struct Scene;
}

namespace ddish::trace_vk {

class VkProbeTracer final : public probes::ProbeUpdater {
 public:
  // The device must have been opened with ray tracing on (gpu::DeviceFeatures::ray_tracing).
  // Throws gpu::GpuError for a device without ray tracing. The scene is posed; the device
  // outlives the tracer.
  VkProbeTracer(const gpu::Device& device, const scene::Scene& scene, const trace::PathOptions& path,
                const probes::UpdateOptions& options);
  ~VkProbeTracer() override;

  const probes::UpdateOptions& options() const override { return options_; }
  void set_options(const probes::UpdateOptions& options) override;

  using probes::ProbeUpdater::update;
  probes::UpdateStats update(probes::ProbeVolume& volume, std::span<const std::uint32_t> probes) const override;

  // Follows the scene posed at a new time: instance transforms (the top-level structure is
  // rebuilt), the vertices of deformed meshes whose pose_version changed (their bottom-level
  // structures are refitted), emissive triangles and lights. `scene` is the one the tracer was
  // made for.
  void scene_posed(const scene::Scene& scene, std::span<const int> moved);

  // The running average on the GPU: probe after probe, coefficient after coefficient, RGB as
  // three floats (probes::ProbeVolume's layout), for the volume of the last update.
  const gpu::Buffer& coefficient_buffer() const;
  // Its distance moments: probe after probe, texel after texel, (mean d, mean d^2) over the
  // range as two floats (a 16-byte placeholder for a volume without moments).
  const gpu::Buffer& moment_buffer() const;

  // Off (the default): every update copies the updated probes' coefficients and moments into the
  // host volume. On: they stay on the GPU and the host volume's values of the probes updated
  // since the last read_back() are stale; nothing else may write them meanwhile, and update()
  // of another volume throws std::logic_error until they are read back.
  void defer_host_copy(bool defer);
  // Brings the volume's coefficients and moments up to date with the GPU's (a whole-buffer copy,
  // then the stale probes'), when some are stale; `volume` is the one the tracer updates.
  void read_back(probes::ProbeVolume& volume) const;
  // Probes whose host values are stale (deferred copies since the last read_back()).
  std::size_t stale_probes() const;

  // Rays cast so far (path, bounce and shadow rays).
  std::uint64_t rays_traced() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  probes::UpdateOptions options_;
};

}  // namespace ddish::trace_vk
