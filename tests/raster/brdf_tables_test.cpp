// BrdfTables and brdf_dfg on the GPU (brdf_dfg, brdf_ggx_zh of
// probe_lighting.glsl) against independent CPU integrals of trace::Bsdf and trace's albedo table.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>

#include "probe_lighting_harness.h"
#include "probe_test_util.h"
#include "sh/ggx_zh.h"
#include "trace/bsdf.h"
#include "trace/ggx.h"
#include "trace/specular_albedo.h"

namespace ddish::raster::test {
namespace {

// (scale, bias) of trace::Bsdf itself: its specular lobe f (with base colour 1 and metallic 1,
// F = 1; with base colour 0, F = (1 - v.h)^5) times cos, over the density trace::Ggx gives
// reflections of visible normals, on an n x n midpoint grid. Unlike integrate_dfg it evaluates
// the BSDF and the density separately rather than their ratio F G2 / G1.
glm::dvec2 reference_dfg(float n_dot_v, float roughness, int n) {
  const trace::Bsdf white({glm::vec3(1.0f), 1.0f, roughness});
  const trace::Bsdf black({glm::vec3(0.0f), 1.0f, roughness});
  const trace::Ggx ggx(trace::Ggx::alpha_from_roughness(roughness));
  const float mu = std::max(n_dot_v, 1e-6f);
  const glm::vec3 wo(std::sqrt(1.0f - mu * mu), 0.0f, mu);
  glm::dvec2 sum(0.0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const glm::vec2 u((float(i) + 0.5f) / float(n), (float(j) + 0.5f) / float(n));
      const glm::vec3 h = ggx.sample_visible_normal(wo, u);
      const glm::vec3 wi = glm::normalize(2.0f * glm::dot(wo, h) * h - wo);
      if (wi.z <= 0.0f) continue;
      const double pdf = ggx.reflected_pdf(wo, h);
      if (!(pdf > 0.0)) continue;
      const double f1 = white.eval_specular(wo, wi).x, f0 = black.eval_specular(wo, wi).x;
      sum += glm::dvec2(f1 - f0, f0) * (double(wi.z) / pdf);
    }
  return sum / (double(n) * n);
}

class BrdfTablesTest : public ProbeGpuTest {
 protected:
  std::vector<glm::vec4> run(const std::vector<Query>& queries) {
    probes::ProbeVolume volume;  // one probe; the tables do not read it
    ProbeTextures textures(device(), volume);
    textures.upload(runner(), volume);
    return Harness(device(), textures, brdf(), 2).run(runner(), queries);
  }
};

// (e): the GPU table (bilinear between fp16 nodes) against the Bsdf quadrature, at nodes and
// between them, over the whole range of n.v and roughness.
TEST_F(BrdfTablesTest, DfgMatchesBsdfQuadrature) {
  const float nvs[] = {0.02f, 0.1f, 0.25f, 0.37f, 0.5f, 0.71f, 0.9f, 1.0f};
  const float rs[] = {0.0f, 0.05f, 0.16f, 0.3f, 0.45f, 0.6f, 0.83f, 1.0f};
  std::vector<Query> queries;
  for (float nv : nvs)
    for (float r : rs) queries.push_back(table_query(Kind::dfg, nv, r));
  const auto results = run(queries);
  double worst_gpu = 0.0, worst_grazing = 0.0, worst_cpu = 0.0;
  std::size_t q = 0;
  for (float nv : nvs)
    for (float r : rs) {
      const glm::dvec2 ref = reference_dfg(nv, r, 512);
      const glm::dvec2 cpu = glm::dvec2(brdf().dfg().lookup(nv, r));
      const glm::dvec2 gpu = glm::dvec2(results[q].x, results[q].y);
      const double e_gpu = std::max(std::abs(gpu.x - ref.x), std::abs(gpu.y - ref.y));
      const double e_cpu = std::max(std::abs(cpu.x - ref.x), std::abs(cpu.y - ref.y));
      // Grazing views of near-mirrors are where bilinear interpolation between 32 x 32 nodes
      // errs most (8e-3 at n.v 0.02, roughness 0.05); elsewhere the nodes' own quadrature error.
      EXPECT_LT(e_gpu, nv < 0.05f ? 1e-2 : 5e-3) << "n.v " << nv << " roughness " << r;
      (nv < 0.05f ? worst_grazing : worst_gpu) =
          std::max(nv < 0.05f ? worst_grazing : worst_gpu, e_gpu);
      worst_cpu = std::max(worst_cpu, e_cpu);
      ++q;
    }
  std::printf("[ dfg ] largest |table - Bsdf quadrature|: GPU %.2e (n.v >= 0.05), %.2e (n.v "
              "0.02); CPU lookup %.2e\n", worst_gpu, worst_grazing, worst_cpu);
}

// The table's own convergence and cost: the default 64 x 64 samples per node against 256 x 256
// (every other node in n.v, every third in roughness).
TEST_F(BrdfTablesTest, DfgNodesConverged) {
  const DfgTable& table = brdf().dfg();
  double worst = 0.0;
  for (int j = 0; j < table.size; j += 3)
    for (int i = 0; i < table.size; i += 2) {
      const float x = float(i) / float(table.size - 1), r = float(j) / float(table.size - 1);
      const glm::vec2 err = glm::abs(integrate_dfg(x * x * x, r, 256) - table.node(i, j));
      worst = std::max(worst, double(std::max(err.x, err.y)));
    }
  // The midpoint rule converges like 1 / n where the reflected lobe crosses the horizon.
  EXPECT_LT(worst, 4e-3);
  const auto start = std::chrono::steady_clock::now();
  const DfgTable again = compute_dfg_table();
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(again.values.size(), table.values.size());
  std::printf("[ dfg ] %dx%d nodes, %d samples each: %.1f ms; node error vs 256^2 samples %.2e\n",
              table.size, table.size, DfgTable::kDefaultQuadrature * DfgTable::kDefaultQuadrature,
              ms, worst);
}

// With the diffuse scale 1 - E(n.v, roughness) that the forward shader reads from trace's table,
// the DFG table conserves energy for a white dielectric: (0.04 scale + bias) + (1 - E) = 1.
TEST_F(BrdfTablesTest, DfgConservesEnergyWithTracerAlbedo) {
  const auto& albedo = trace::DielectricSpecularAlbedo::get();
  std::mt19937 rng(3u);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Query> queries;
  std::vector<glm::vec2> points;
  for (int q = 0; q < 200; ++q) {
    points.emplace_back(q < 2 ? float(q) : u(rng), q == 2 ? 0.0f : (q == 3 ? 1.0f : u(rng)));
    queries.push_back(table_query(Kind::dfg, points.back().x, points.back().y));
  }
  const auto results = run(queries);
  double worst_energy = 0.0;
  for (std::size_t q = 0; q < points.size(); ++q) {
    const float scale = 1.0f - albedo.directional(points[q].x, points[q].y);
    if (points[q].x > 0.1f) {  // trace's table is within 0.001 of its integral there
      const glm::vec2 dfg(results[q]);
      const double energy = 0.04 * dfg.x + dfg.y + scale;
      EXPECT_NEAR(energy, 1.0, 6e-3) << "n.v " << points[q].x << " roughness " << points[q].y;
      worst_energy = std::max(worst_energy, std::abs(energy - 1.0));
    }
  }
  std::printf("[ dfg + diffuse scale ] white dielectric energy off by %.2e\n", worst_energy);
}

// brdf_ggx_zh interpolates the same nodes the same way as sh::ggx_zh.
TEST_F(BrdfTablesTest, GgxZhMatchesCpu) {
  std::vector<Query> queries;
  for (int i = 0; i <= 200; ++i) queries.push_back(table_query(Kind::ggx_zh, 0.0f, i / 200.0f));
  const auto results = run(queries);
  float worst = 0.0f;
  for (int i = 0; i <= 200; ++i) {
    const sh::BandScales k = sh::ggx_zh(i / 200.0f);
    for (int l = 1; l <= 4; ++l) {
      EXPECT_NEAR(results[std::size_t(i)][l - 1], k[std::size_t(l)], 2e-6f) << "r " << i / 200.0f;
      worst = std::max(worst, std::abs(results[std::size_t(i)][l - 1] - k[std::size_t(l)]));
    }
  }
  std::printf("[ ggx zh ] largest |GPU - sh::ggx_zh| %.2e\n", worst);
}

}  // namespace
}  // namespace ddish::raster::test
