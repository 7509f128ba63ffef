#include "probes/tracer_source.h"

namespace ddish::probes {

trace::PathSample TracerSource::trace_path(const trace::Ray& ray, trace::Sampler& sampler) const {
  return tracer_.trace_path(ray, sampler);
}

std::uint64_t TracerSource::rays_traced() const { return tracer_.rays_traced(); }

}  // namespace ddish::probes
