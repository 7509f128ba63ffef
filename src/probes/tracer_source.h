// The path tracer (trace::Tracer) as the probes' radiance source: what `ddish probes`, the
// renderer and the server update probes with.
#pragma once

#include "probes/probe_tracer.h"
#include "trace/tracer.h"

namespace ddish::probes {

class TracerSource final : public RadianceSource {
 public:
  explicit TracerSource(const trace::Tracer& tracer) : tracer_(tracer) {}
  trace::PathSample trace_path(const trace::Ray& ray, trace::Sampler& sampler) const override;
  std::uint64_t rays_traced() const override;

 private:
  const trace::Tracer& tracer_;
};

}  // namespace ddish::probes
