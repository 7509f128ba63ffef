// Radiance sources for probe tests that need no scene: the environment seen from everywhere,
// optionally changed between updates, with a ray counter like the tracer's.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>

#include "probes/probe_tracer.h"

namespace ddish::probes::synthetic {

class FunctionSource final : public RadianceSource {
 public:
  using Function = std::function<trace::PathSample(const trace::Ray&, trace::Sampler&)>;
  explicit FunctionSource(Function f) : f_(std::move(f)) {}

  trace::PathSample trace_path(const trace::Ray& ray, trace::Sampler& sampler) const override {
    rays_.fetch_add(1, std::memory_order_relaxed);
    return f_(ray, sampler);
  }
  std::uint64_t rays_traced() const override { return rays_.load(); }

 private:
  Function f_;
  mutable std::atomic<std::uint64_t> rays_{0};
};

// Uniform radiance from every direction, no geometry.
inline trace::PathSample uniform(const glm::vec3& radiance) {
  trace::PathSample s;
  s.radiance = radiance;
  return s;
}

}  // namespace ddish::probes::synthetic
