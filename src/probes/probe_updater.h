// The probe update behind one interface (DESIGN.md: "the tracer sits behind an interface"): the
// CPU probe tracer (probe_tracer.h, Embree paths through a RadianceSource) and the GPU one
// (trace_vk/vk_probe_tracer.h, Vulkan ray-tracing pipelines) both take a volume and a list of
// probes and leave the volume updated, with the same options, statistics, classification and
// running average. The scheduler and the frame loop's probe source see only this.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "probes/probe_volume.h"

namespace ddish::probes {

struct UpdateOptions;
struct UpdateStats;

class ProbeUpdater {
 public:
  virtual ~ProbeUpdater() = default;

  virtual const UpdateOptions& options() const = 0;
  // Throws std::invalid_argument for options check_update_options rejects.
  virtual void set_options(const UpdateOptions& options) = 0;

  // One update of the listed probes (the scheduler's choice); inactive and repeated ones are
  // skipped, indices outside the volume throw std::out_of_range. Every probe ages by one; the
  // updated ones restart at age 0. Probes not classified yet are classified by this update.
  virtual UpdateStats update(ProbeVolume& volume, std::span<const std::uint32_t> probes) const = 0;

  // One update of every active probe.
  UpdateStats update_all(ProbeVolume& volume) const;
};

// The probes an update traces: the active ones of `probes`, each once (two tasks on one probe
// would race), in the order given. Throws std::out_of_range for an index outside the volume.
std::vector<std::uint32_t> probes_to_update(const ProbeVolume& volume,
                                            std::span<const std::uint32_t> probes);

}  // namespace ddish::probes
