// The dielectric layer of any F0 and weight (KHR_materials_ior, KHR_materials_specular): the
// table's dE/dF0 against quadrature, the layer's albedo linear in F0, and the white furnace
// still 1 whatever F0 (coloured too) and weight, since the diffuse base gets exactly what the
// layer lets through.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "bsdf_test_util.h"
#include "trace/bsdf.h"
#include "trace/specular_albedo.h"

using namespace ddish::trace;
using ddish::trace::bsdf_test::direction;
using ddish::trace::bsdf_test::sampled_albedo;

namespace {

TEST(DielectricLayer, SlopeTableMatchesQuadrature) {
  const auto& table = DielectricSpecularAlbedo::get();
  double worst = 0.0;
  for (float roughness : {0.05f, 0.3f, 0.7f, 1.0f})
    for (float mu : {1.0f, 0.5f, 0.2f, 0.05f}) {
      // E(F0 = 1) - E(F0 = 0) by direct quadrature, against the interpolated table.
      const double reference = DielectricSpecularAlbedo::integrate_f0(mu, roughness, 128, 1.0f) -
                               DielectricSpecularAlbedo::integrate_f0(mu, roughness, 128, 0.0f);
      const double error = std::abs(reference - table.directional_slope(mu, roughness));
      worst = std::max(worst, error);
      EXPECT_LT(error, 0.01) << "roughness " << roughness << " mu " << mu;
      // E is linear in F0: the F0 = 0.25 layer is E(0.04) + 0.21 dE/dF0, to quadrature precision.
      const double e25 = DielectricSpecularAlbedo::integrate_f0(mu, roughness, 64, 0.25f);
      const double e04 = DielectricSpecularAlbedo::integrate_f0(mu, roughness, 64, 0.04f);
      const double slope = DielectricSpecularAlbedo::integrate_f0(mu, roughness, 64, 1.0f) -
                           DielectricSpecularAlbedo::integrate_f0(mu, roughness, 64, 0.0f);
      EXPECT_NEAR(e25, e04 + 0.21 * slope, 1e-9);
    }
  // At normal incidence and roughness 0 the layer reflects F0 exactly: dE/dF0 = 1.
  EXPECT_NEAR(table.directional_slope(1.0f, 0.0f), 1.0f, 2e-3f);
  std::cout << "[ figures  ] dE/dF0 table against quadrature: largest error " << worst << "\n";
}

TEST(DielectricLayer, WhiteFurnaceIsOneForAnyF0AndWeight) {
  double worst = 0.0;
  std::uint64_t stream = 7000;
  struct Layer {
    glm::vec3 f0;
    float weight;
  };
  // ior 2 (F0 1/9), ior 3 (1/4), a coloured layer, half and no weight.
  const Layer layers[] = {{glm::vec3(1.0f / 9.0f), 1.0f},
                          {glm::vec3(0.25f), 1.0f},
                          {glm::vec3(0.04f, 0.2f, 0.5f), 1.0f},
                          {glm::vec3(0.04f), 0.5f},
                          {glm::vec3(0.1f), 0.0f}};
  for (const Layer& layer : layers)
    for (float roughness : {0.05f, 0.5f, 1.0f})
      for (float cos_o : {1.0f, 0.5f, 0.1f}) {
        BsdfParams p{glm::vec3(1.0f), 0.0f, roughness};
        p.dielectric_f0 = layer.f0;
        p.specular = layer.weight;
        const Bsdf bsdf(p);
        const auto a = sampled_albedo(bsdf, direction(cos_o, 1.0f), 40000, ++stream);
        for (int k = 0; k < 3; ++k) {
          worst = std::max(worst, std::abs(a.mean[k] - 1.0));
          EXPECT_NEAR(a.mean[k], 1.0, 0.01 + 4.0 * a.std_error)
              << "F0 " << layer.f0[k] << " weight " << layer.weight << " roughness " << roughness
              << " cos " << cos_o;
        }
      }
  std::cout << "[ figures  ] white furnace over F0 and weights: largest |albedo - 1| = " << worst << "\n";
}

// The specular lobe alone: a black dielectric of F0 1/9 reflects (1/9) / 0.04 times the default
// layer's specular at normal incidence, and half the weight halves it.
TEST(DielectricLayer, SpecularLobeScalesWithF0AndWeight) {
  const glm::vec3 wo = direction(1.0f), wi = direction(0.999f, 2.0f);
  BsdfParams base{glm::vec3(0.0f), 0.0f, 0.6f};
  const float f_default = Bsdf(base).eval_specular(wo, wi).x;
  BsdfParams ior2 = base;
  ior2.dielectric_f0 = glm::vec3(1.0f / 9.0f);
  BsdfParams half = base;
  half.specular = 0.5f;
  // Schlick at v.h ~ 1: (1 - v.h)^5 is below 1e-12 here, so F = F0 to float precision.
  EXPECT_NEAR(Bsdf(ior2).eval_specular(wo, wi).x / f_default, (1.0f / 9.0f) / 0.04f, 1e-4f);
  EXPECT_NEAR(Bsdf(half).eval_specular(wo, wi).x / f_default, 0.5f, 1e-5f);
}

}  // namespace
