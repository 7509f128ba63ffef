// The probe update against synthetic radiance sources: analytic SH of a uniform environment,
// determinism, the running average's recurrence, classification, and scheduler subsets.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numbers>
#include <vector>

#include <tbb/global_control.h>

#include "probes/fibonacci.h"
#include "probes/probe_tracer.h"
#include "sh/basis.h"
#include "synthetic_sources.h"

using namespace ddish::probes;
using ddish::probes::synthetic::FunctionSource;
namespace synthetic = ddish::probes::synthetic;
using ddish::scene::Aabb;
using ddish::trace::PathSample;
using ddish::trace::Ray;
using ddish::trace::Sampler;

namespace {

ProbeVolume small_volume(int order = 2) {
  return ProbeVolume(ProbeGrid(Aabb{{-1.0f, -1.0f, -1.0f}, {1.0f, 1.0f, 1.0f}}, {3, 2, 2}), order);
}

// Quadrature error bound of the unrotated n-point lattice for band l: the norm over m of
// (4π/n) Σ_i Y_lm(d_i). The sum over a rotated lattice is a rotation (Wigner D, orthogonal
// within the band) of these sums, so no rotation can make any |c_lm| larger than this norm.
double lattice_band_error(std::uint32_t n, int l) {
  std::vector<double> sums(ddish::sh::kMaxCoeffs, 0.0);
  double y[ddish::sh::kMaxCoeffs];
  for (std::uint32_t i = 0; i < n; ++i) {
    ddish::sh::eval_basis(glm::dvec3(fibonacci_direction(i, n)), 4, y);
    for (int j = 0; j < ddish::sh::kMaxCoeffs; ++j) sums[std::size_t(j)] += y[j];
  }
  double norm2 = 0.0;
  for (int m = -l; m <= l; ++m) {
    double e = sums[std::size_t(ddish::sh::sh_index(l, m))] * 4.0 * std::numbers::pi / n;
    norm2 += e * e;
  }
  return std::sqrt(norm2);
}

bool bit_identical(const ProbeVolume& a, const ProbeVolume& b) {
  auto ca = a.all_coefficients(), cb = b.all_coefficients();
  return ca.size() == cb.size() && std::memcmp(ca.data(), cb.data(), ca.size_bytes()) == 0;
}

}  // namespace

TEST(ProbeUpdate, UniformEnvironmentGivesAnalyticSh) {
  // Radiance L from every direction: c_00 = ∫ L Y_00 dω = L · 0.2820948 · 4π = L · sqrt(4π);
  // every higher coefficient integrates to zero.
  const glm::vec3 L(0.5f, 2.0f, 7.25f);
  const std::uint32_t n = 256;
  FunctionSource source([&](const Ray&, Sampler&) { return synthetic::uniform(L); });
  ProbeVolume volume = small_volume(4);
  ProbeTracer tracer(source, UpdateOptions{.samples = n, .seed = 11});
  UpdateStats stats = tracer.update(volume);
  EXPECT_EQ(stats.probes_traced, 12u);
  EXPECT_EQ(stats.paths, 12u * n);
  EXPECT_EQ(stats.rays, 12u * n);
  EXPECT_EQ(volume.active_count(), 12u);

  const float sqrt4pi = std::sqrt(4.0f * std::numbers::pi_v<float>);
  // fp32 rounding of the basis values and the weights: a few ulps of the largest term.
  const float rounding = 1e-5f * L.z;
  for (int l = 1; l <= 4; ++l) {
    double bound = lattice_band_error(n, l);
    // The lattice integrates bands 1..4 to below 5e-3 (relative to the function's magnitude)
    // at 256 points; independent random directions would leave ~ sqrt(4π/256) = 0.22 per
    // coefficient.
    EXPECT_LT(bound, 5e-3) << "band " << l;
  }
  for (std::uint32_t p = 0; p < volume.probe_count(); ++p) {
    ddish::sh::ShRgb c = volume.sh(p);
    for (int ch = 0; ch < 3; ++ch) {
      EXPECT_NEAR(c[0][ch], L[ch] * sqrt4pi, 2e-6f * L[ch] * sqrt4pi) << "probe " << p;
      for (int i = 1; i < 25; ++i) {
        int l = ddish::sh::band_of(i);
        ASSERT_LE(std::abs(c[i][ch]), L[ch] * lattice_band_error(n, l) + rounding)
            << "probe " << p << " coefficient " << i;
      }
    }
  }
}

TEST(ProbeUpdate, SameSeedSameCoefficientsWhateverTheThreads) {
  // Radiance that depends on direction and on the sampler (like a path tracer's noise).
  FunctionSource source([](const Ray& r, Sampler& s) {
    return synthetic::uniform(glm::vec3(1.0f + r.direction.x, s.next1d(), 2.0f * s.next1d()));
  });
  auto run = [&](std::uint64_t seed, int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
    ProbeVolume v = small_volume();
    ProbeTracer t(source, UpdateOptions{.samples = 64, .seed = seed});
    for (int k = 0; k < 3; ++k) t.update(v);
    return v;
  };
  ProbeVolume a = run(5, 1), b = run(5, 4), c = run(6, 4);
  EXPECT_TRUE(bit_identical(a, b));
  EXPECT_FALSE(bit_identical(a, c));
  // Different seeds differ in every probe, not just somewhere.
  for (std::uint32_t p = 0; p < a.probe_count(); ++p)
    EXPECT_NE(a.coefficients(p)[1], c.coefficients(p)[1]) << "probe " << p;
}

TEST(ProbeUpdate, RunningAverageFollowsRecurrence) {
  // A uniform environment whose radiance changes every update: the estimate of update k is
  // exactly e_k = L_k sqrt(4π) in c_00, so the average must follow
  // A_k = (1 - w_k) A_{k-1} + w_k e_k with w_k = max(1/k, 1 - alpha).
  const float alpha = 0.8f;  // 1/k >= 0.2 up to k = 5, then the exponential average
  float radiance = 0.0f;
  FunctionSource source([&](const Ray&, Sampler&) { return synthetic::uniform(glm::vec3(radiance)); });
  ProbeVolume volume = small_volume(1);
  ProbeTracer tracer(source, UpdateOptions{.samples = 32, .hysteresis = alpha});
  const double sqrt4pi = std::sqrt(4.0 * std::numbers::pi);
  double expected = 0.0;
  for (std::uint32_t k = 1; k <= 30; ++k) {
    radiance = float(1.0 + 0.5 * std::sin(0.7 * k) + (k > 12 ? 3.0 : 0.0));  // a step at k = 13
    tracer.update(volume);
    double w = std::max(1.0 / k, 1.0 - alpha);
    expected = (1.0 - w) * expected + w * double(radiance) * sqrt4pi;
    for (std::uint32_t p = 0; p < volume.probe_count(); ++p) {
      ASSERT_NEAR(volume.coefficients(p)[0].x, expected, 1e-5 * expected) << "update " << k;
      ASSERT_EQ(volume.state(p).updates, k);
      ASSERT_EQ(volume.state(p).samples, 32u * k);
    }
  }
  // For the first 5 updates it is the plain mean: check against the mean explicitly.
  ProbeVolume fresh = small_volume(1);
  double sum = 0.0;
  for (std::uint32_t k = 1; k <= 5; ++k) {
    radiance = float(k * k);
    sum += double(radiance);
    tracer.update(fresh);
  }
  EXPECT_NEAR(fresh.coefficients(0)[0].x, sum / 5.0 * sqrt4pi, 1e-5 * sum);
}

TEST(ProbeUpdate, BackFacingProbesBecomeInactiveAndAreNotTracedAgain) {
  // Probes with x < 0 see back faces in 60% of directions, the rest in 10%.
  FunctionSource source([](const Ray& r, Sampler&) {
    PathSample s = synthetic::uniform(glm::vec3(1.0f));
    s.hit = true;
    s.backface = r.origin.x < 0.0f ? r.direction.z < 0.2f : r.direction.z > 0.8f;
    return s;
  });
  ProbeVolume volume = small_volume();  // x counts 3: x = -2/3, 0, +2/3
  ProbeTracer tracer(source, UpdateOptions{.samples = 200});
  UpdateStats first = tracer.update(volume);
  EXPECT_EQ(first.probes_traced, 12u);
  EXPECT_EQ(first.newly_inactive, 4u);
  EXPECT_EQ(volume.inactive_count(), 4u);
  EXPECT_EQ(volume.inside_geometry_count(), 4u);
  for (std::uint32_t p = 0; p < volume.probe_count(); ++p) {
    const ProbeState& s = volume.state(p);
    bool inside = volume.grid().position(p).x < 0.0f;
    EXPECT_EQ(s.active(), !inside) << p;
    EXPECT_FALSE(s.unclassified());
    // Cap areas 0.6 and 0.1 of the sphere; a rotated 200-point lattice hits them within ~2%.
    EXPECT_NEAR(s.backface_fraction, inside ? 0.6f : 0.1f, 0.03f);
    if (inside) {
      EXPECT_EQ(s.updates, 0u);
      for (const glm::vec3& c : volume.coefficients(p)) EXPECT_EQ(c, glm::vec3(0.0f));
    }
  }
  // Later updates trace the 8 active probes only, and do not classify again.
  std::uint64_t before = source.rays_traced();
  UpdateStats second = tracer.update(volume);
  EXPECT_EQ(second.probes_traced, 8u);
  EXPECT_EQ(second.newly_inactive, 0u);
  EXPECT_EQ(source.rays_traced() - before, 8u * 200u);
  // Re-running classification looks at every probe again: the inside ones are found again, the
  // others keep accumulating (their third update).
  volume.reset_classification();
  EXPECT_EQ(volume.active_count(), 12u);
  UpdateStats third = tracer.update(volume);
  EXPECT_EQ(third.probes_traced, 12u);
  EXPECT_EQ(third.newly_inactive, 4u);
  for (std::uint32_t p = 0; p < volume.probe_count(); ++p)
    EXPECT_EQ(volume.state(p).updates, volume.state(p).active() ? 3u : 0u) << p;
}

TEST(ProbeUpdate, SubsetUpdateAgesTheRest) {
  FunctionSource source([](const Ray&, Sampler&) { return synthetic::uniform(glm::vec3(1.0f)); });
  ProbeVolume volume = small_volume();
  ProbeTracer tracer(source, UpdateOptions{.samples = 16});
  tracer.update(volume);
  std::vector<std::uint32_t> pick = {2, 5, 5, 7};  // a repeat is traced once
  UpdateStats stats = tracer.update(volume, pick);
  EXPECT_EQ(stats.probes_traced, 3u);
  EXPECT_EQ(stats.frame, 2u);
  EXPECT_EQ(volume.frame(), 2u);
  for (std::uint32_t p = 0; p < volume.probe_count(); ++p) {
    bool picked = p == 2 || p == 5 || p == 7;
    EXPECT_EQ(volume.state(p).age, picked ? 0u : 1u) << p;
    EXPECT_EQ(volume.state(p).updates, picked ? 2u : 1u) << p;
  }
  std::vector<std::uint32_t> bad = {12};
  EXPECT_THROW(tracer.update(volume, bad), std::out_of_range);
}

TEST(ProbeUpdate, NonFiniteSamplesAreDroppedAndReported) {
  FunctionSource source([](const Ray& r, Sampler&) {
    return synthetic::uniform(glm::vec3(r.direction.y > 0.9f ? std::nanf("") : 1.0f));
  });
  ProbeVolume volume = small_volume();
  UpdateStats stats = ProbeTracer(source, UpdateOptions{.samples = 100}).update(volume);
  EXPECT_GT(stats.invalid_samples, 0u);
  for (std::uint32_t p = 0; p < volume.probe_count(); ++p)
    for (const glm::vec3& c : volume.coefficients(p))
      ASSERT_TRUE(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z));
}

TEST(ProbeUpdate, RejectsBadOptions) {
  FunctionSource source([](const Ray&, Sampler&) { return synthetic::uniform(glm::vec3(1.0f)); });
  EXPECT_THROW(ProbeTracer(source, UpdateOptions{.samples = 0}), std::invalid_argument);
  EXPECT_THROW(ProbeTracer(source, UpdateOptions{.hysteresis = 1.0f}), std::invalid_argument);
  EXPECT_THROW(ProbeVolume(ProbeGrid(Aabb{{0, 0, 0}, {1, 1, 1}}, {1, 1, 1}), 7),
               std::invalid_argument);
  EXPECT_THROW(ProbeVolume(ProbeGrid(Aabb{{0, 0, 0}, {1, 1, 1}}, {1, 1, 1}), 0),
               std::invalid_argument);
}
