// Comparing two probe tracers within Monte Carlo error, over many probes at once. Each tracer
// updates a fresh volume R times with hysteresis 0 (every update replaces the average), so each
// probe yields R independent single-update estimates of every SH coefficient; their means are
// compared with Welch's z = (mean_a - mean_b) / sqrt(var_a / R + var_b / R), the variances
// estimated from the same R updates. Under "both tracers estimate the same integral" each z is
// close to a Student t with about 2R - 2 degrees of freedom, so the mean of z^2 over all
// probes, coefficients and channels is close to 1 (nu / (nu - 2)) and |z| > 4 is rare.
// A bias shows as a mean z^2 that grows with the bias squared times R over the variance. A
// global bias (too bright, too dark) shows best in the pooled z of the probes' L0 green terms,
// weighted by inverse variance: sum(d / se^2) / sqrt(sum(1 / se^2)), d = mean_a - mean_b. The
// probes' paths are independent, so under the null hypothesis it is close to a standard normal,
// while a bias adds up over the probes (the quiet probes weigh most).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "probes/probe_tracer.h"
#include "probes/probe_updater.h"
#include "probes/probe_volume.h"

namespace ddish::trace_vk::test {

// R single-update estimates per probe: [probe][update][coefficient * 3 + channel]; a probe
// found inside geometry has none.
struct Estimates {
  std::vector<std::vector<std::vector<double>>> values;
};

inline Estimates single_update_estimates(const probes::ProbeUpdater& updater, const probes::ProbeGrid& grid,
                                         int order, int updates) {
  probes::ProbeVolume volume(grid, order);
  Estimates e;
  e.values.resize(volume.probe_count());
  for (int r = 0; r < updates; ++r) {
    updater.update_all(volume);
    for (std::uint32_t p = 0; p < volume.probe_count(); ++p) {
      if (!volume.state(p).active()) continue;
      std::vector<double> v;
      for (const glm::vec3& c : volume.coefficients(p))
        for (int ch = 0; ch < 3; ++ch) v.push_back(c[ch]);
      e.values[p].push_back(std::move(v));
    }
  }
  return e;
}

struct Comparison {
  int terms = 0;          // probe x coefficient x channel terms compared
  int probes = 0;         // probes active for both tracers
  int classified_apart = 0;  // probes one tracer found inside geometry and the other did not
  double mean_z2 = 0.0;
  double max_abs_z = 0.0;
  double mean_z2_scaled = 0.0;  // the same with tracer a's means scaled by `scale`
  double pooled_z = 0.0;         // over the probes' L0 green terms
  double pooled_z_scaled = 0.0;  // the same with tracer a's means scaled by `scale`
  std::string worst;            // where max_abs_z is
};

// `scale`: a deliberate bias to show what the test would see (e.g. 1.05: 5 % too bright).
inline Comparison compare(const Estimates& a, const Estimates& b, double scale) {
  Comparison c;
  double sum_z2 = 0.0, sum_z2_scaled = 0.0;
  double pooled_diff = 0.0, pooled_diff_scaled = 0.0, pooled_weight = 0.0;
  for (std::size_t p = 0; p < a.values.size(); ++p) {
    const auto& ea = a.values[p];
    const auto& eb = b.values[p];
    const bool inside_a = ea.empty(), inside_b = eb.empty();
    if (inside_a != inside_b) ++c.classified_apart;
    if (inside_a || inside_b || ea.size() != eb.size()) continue;
    ++c.probes;
    const double r = double(ea.size());
    for (std::size_t t = 0; t < ea[0].size(); ++t) {
      double ma = 0, mb = 0;
      for (std::size_t k = 0; k < ea.size(); ++k) {
        ma += ea[k][t];
        mb += eb[k][t];
      }
      ma /= r;
      mb /= r;
      double va = 0, vb = 0;
      for (std::size_t k = 0; k < ea.size(); ++k) {
        va += (ea[k][t] - ma) * (ea[k][t] - ma);
        vb += (eb[k][t] - mb) * (eb[k][t] - mb);
      }
      va /= r - 1.0;
      vb /= r - 1.0;
      const double se2 = va / r + vb / r;
      // A term with no variance on either side (an exact zero, a pure sky term) says nothing.
      if (!(se2 > 1e-20 * (ma * ma + mb * mb + 1e-30))) continue;
      const double z = (ma - mb) / std::sqrt(se2);
      const double zs = (ma * scale - mb) / std::sqrt(se2);
      ++c.terms;
      if (t == 1) {  // L0, green
        pooled_diff += (ma - mb) / se2;
        pooled_diff_scaled += (ma * scale - mb) / se2;
        pooled_weight += 1.0 / se2;
      }
      sum_z2 += z * z;
      sum_z2_scaled += zs * zs;
      if (std::abs(z) > c.max_abs_z) {
        c.max_abs_z = std::abs(z);
        c.worst = "probe " + std::to_string(p) + " coefficient " + std::to_string(t / 3) + " channel " +
                  std::to_string(t % 3) + ": " + std::to_string(ma) + " vs " + std::to_string(mb);
      }
    }
  }
  if (c.terms > 0) {
    c.mean_z2 = sum_z2 / c.terms;
    c.mean_z2_scaled = sum_z2_scaled / c.terms;
  }
  if (pooled_weight > 0.0) {
    c.pooled_z = pooled_diff / std::sqrt(pooled_weight);
    c.pooled_z_scaled = pooled_diff_scaled / std::sqrt(pooled_weight);
  }
  return c;
}

}  // namespace ddish::trace_vk::test
