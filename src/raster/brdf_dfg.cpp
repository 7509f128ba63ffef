#include "raster/brdf_dfg.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "trace/ggx.h"

namespace ddish::raster {

glm::vec2 integrate_dfg(float n_dot_v, float roughness, int n) {
  const float mu = std::clamp(n_dot_v, 1e-6f, 1.0f);
  const trace::Ggx ggx(trace::Ggx::alpha_from_roughness(roughness));
  const glm::vec3 wo(std::sqrt(1.0f - mu * mu), 0.0f, mu);
  const float g1 = ggx.g1(wo);
  double scale = 0.0, bias = 0.0;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const glm::vec2 u((float(i) + 0.5f) / float(n), (float(j) + 0.5f) / float(n));
      const glm::vec3 h = ggx.sample_visible_normal(wo, u);
      const float wo_h = glm::dot(wo, h);
      const glm::vec3 wi = 2.0f * wo_h * h - wo;
      if (wi.z <= 0.0f) continue;  // reflected below the horizon: no contribution
      const float m = 1.0f - std::clamp(wo_h, 0.0f, 1.0f);
      const float schlick = m * m * m * m * m;
      const double weight = double(ggx.g2(wo, wi) / g1);
      scale += weight * (1.0 - schlick);
      bias += weight * schlick;
    }
  }
  const double inv = 1.0 / (double(n) * double(n));
  return {float(scale * inv), float(bias * inv)};
}

glm::vec2 DfgTable::lookup(float n_dot_v, float roughness) const {
  const auto locate = [this](float v, int& i, float& t) {
    const float f = std::clamp(v, 0.0f, 1.0f) * float(size - 1);
    i = std::min(int(f), size - 2);
    t = f - float(i);
  };
  int i, j;
  float ti, tj;
  locate(std::cbrt(std::clamp(n_dot_v, 0.0f, 1.0f)), i, ti);
  locate(roughness, j, tj);
  const glm::vec2 a = glm::mix(node(i, j), node(i + 1, j), ti);
  const glm::vec2 b = glm::mix(node(i, j + 1), node(i + 1, j + 1), ti);
  return glm::mix(a, b, tj);
}

DfgTable compute_dfg_table(int size, int quadrature) {
  if (size < 2 || quadrature < 1)
    throw std::invalid_argument("DFG table needs at least 2 nodes per axis and 1 sample");
  DfgTable table;
  table.size = size;
  table.values.resize(std::size_t(size) * std::size_t(size));
  tbb::parallel_for(0, size, [&](int j) {
    const float roughness = float(j) / float(size - 1);
    for (int i = 0; i < size; ++i) {
      const float x = float(i) / float(size - 1);
      table.values[std::size_t(j * size + i)] = integrate_dfg(x * x * x, roughness, quadrature);
    }
  });
  return table;
}

}  // namespace ddish::raster
