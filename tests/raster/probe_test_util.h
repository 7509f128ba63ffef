// Shared pieces of the probe-lighting tests: a validated GPU fixture with the BRDF tables, a CPU
// model of the shader's trilinear, validity-weighted interpolation, and fp16 helpers.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <random>

#include <glm/glm.hpp>

#include "../gpu/gpu_test.h"
#include "gpu/commands.h"
#include "probes/probe_volume.h"
#include "raster/brdf_dfg.h"
#include "raster/brdf_tables.h"
#include "sh/packing.h"
#include "sh/sh_rgb.h"

namespace ddish::raster::test {

// The DFG table is computed once per test binary; every fixture uploads a copy.
inline const DfgTable& shared_dfg() {
  static const DfgTable table = compute_dfg_table();
  return table;
}

class ProbeGpuTest : public gpu::test::GpuTest {
 protected:
  void SetUp() override {
    GpuTest::SetUp();
    if (HasFatalFailure()) return;
    runner_ = std::make_unique<gpu::CommandRunner>(device());
    brdf_ = std::make_unique<BrdfTables>(device(), *runner_, shared_dfg());
  }
  void TearDown() override {
    brdf_.reset();
    runner_.reset();
    GpuTest::TearDown();
  }
  gpu::CommandRunner& runner() { return *runner_; }
  const BrdfTables& brdf() { return *brdf_; }

 private:
  std::unique_ptr<gpu::CommandRunner> runner_;
  std::unique_ptr<BrdfTables> brdf_;
};

inline float to_fp16(float v) { return sh::half_to_float(sh::float_to_half(v)); }

// A random SH whose band-0 term dominates; values rounded to fp16 when `exact` so that the
// textures hold them without loss.
inline sh::ShRgb random_sh(std::mt19937& rng, int order, float l0, float others, bool exact) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  sh::ShRgb s(order);
  for (int i = 0; i < s.count(); ++i)
    for (int c = 0; c < 3; ++c) {
      const float v = i == 0 ? l0 * (1.5f + 0.5f * u(rng)) : others * u(rng);
      s[i][c] = exact ? to_fp16(v) : v;
    }
  return s;
}

inline glm::vec3 random_direction(std::mt19937& rng) {
  std::normal_distribution<float> n;
  glm::vec3 d;
  do d = glm::vec3(n(rng), n(rng), n(rng)); while (glm::dot(d, d) < 1e-6f);
  return glm::normalize(d);
}

// The shader's interpolation on the CPU: trilinear weights times validity, renormalised, with
// the same look a quarter of the way to the cell centre when all weights vanish. `valid`
// receives whether any weight was left.
inline sh::ShRgb cpu_interpolate(const probes::ProbeVolume& v, const glm::vec3& p, bool& valid) {
  const probes::ProbeGrid& grid = v.grid();
  const glm::vec3 last = glm::vec3(grid.counts()) - 1.0f;
  const glm::vec3 g = glm::clamp(grid.grid_coordinate(p), glm::vec3(0.0f), last);
  auto weighted = [&](const glm::vec3& q, float& w_sum) {
    const glm::vec3 base = glm::clamp(glm::floor(q), glm::vec3(0.0f), glm::max(last - 1.0f, 0.0f));
    const glm::vec3 t = q - base;
    sh::ShRgb sum(v.sh_order());
    w_sum = 0.0f;
    for (int corner = 0; corner < 8; ++corner) {
      glm::ivec3 c;
      float w = 1.0f;
      for (int a = 0; a < 3; ++a) {
        const int up = (corner >> a) & 1;
        c[a] = std::min(int(base[a]) + up, grid.counts()[a] - 1);
        w *= up ? t[a] : 1.0f - t[a];
      }
      const std::uint32_t i = grid.index(c);
      if (!v.state(i).active() || w == 0.0f) continue;
      sum += v.sh(i) * w;
      w_sum += w;
    }
    return sum;
  };
  float w = 0.0f;
  sh::ShRgb s = weighted(g, w);
  if (!(w > 0.0f)) {
    const glm::vec3 base = glm::clamp(glm::floor(g), glm::vec3(0.0f), glm::max(last - 1.0f, 0.0f));
    s = weighted(glm::mix(g, glm::min(base + 0.5f, last), 0.25f), w);
  }
  valid = w > 0.0f;
  return valid ? s * (1.0f / w) : sh::ShRgb(v.sh_order());
}

inline float max_abs(const glm::vec3& v) {
  return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
}

}  // namespace ddish::raster::test
