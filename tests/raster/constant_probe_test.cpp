// Indirect light from probes that all hold one constant radiance L (only the L0 coefficient,
// L * sqrt(4 pi)), on a sphere with no lights, where the answer is known in closed form from the
// tracer's BSDF convention (trace/bsdf.cpp):
//  - diffuse: the albedo-scaled Lambert lobe (1 - m) a / (pi (1 - E_avg)) (1 - E(n.v)) (1 - E(n.l))
//    integrated against L cos over the hemisphere gives (1 - m) a (1 - E(n.v)) L exactly,
//    because the integral of (1 - E(mu)) 2 mu dmu is 1 - E_avg (specular_albedo.h);
//  - specular: the GGX lobe under constant L reflects (F0 A + B) L, (A, B) the split-sum DFG
//    integrals at (n.v, roughness); its prefiltered radiance is L at every roughness since the
//    GGX zonal kernel keeps band 0 unchanged.
// Every pixel of the sphere is checked against these with n.v from the analytic sphere.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "../gpu/gpu_test.h"
#include "probes/probe_grid.h"
#include "probes/probe_volume.h"
#include "raster/brdf_dfg.h"
#include "raster/renderer.h"
#include "raster_scenes.h"
#include "scene/view.h"
#include "sh/sh_rgb.h"
#include "trace/specular_albedo.h"

namespace ddish::raster::test {
namespace {

using gpu::test::GpuTest;

const glm::vec3 kRadiance(0.8f, 1.1f, 1.4f);
constexpr float kRadius = 1.0f;

probes::ProbeVolume constant_volume(const scene::Scene& s) {
  scene::Aabb box = s.bounds();
  box.min -= glm::vec3(0.5f);
  box.max += glm::vec3(0.5f);
  probes::ProbeVolume volume(probes::ProbeGrid(box, {3, 3, 3}), 2);
  sh::ShRgb sh(2);
  sh[0] = kRadiance * std::sqrt(4.0f * kTestPi);  // Y_00 = 1 / sqrt(4 pi)
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i) volume.set_sh(i, sh);
  return volume;
}

struct Checked {
  int pixels = 0;
  int bad = 0;
  double worst = 0.0;
};

// Renders the sphere and compares every pixel with n.v >= 0.2 to expected(n.v).
template <typename Expected>
Checked render_and_check(gpu::Device& device, const scene::Material& material, bool expect_specular,
                         Expected expected) {
  scene::Scene s = one_mesh_scene(uv_sphere(kRadius, 96, 48), material);
  const probes::ProbeVolume volume = constant_volume(s);
  RendererOptions options;
  options.msaa = 1;
  Renderer renderer(device, s, volume, options);
  EXPECT_EQ(renderer.variant().specular_probes, expect_specular);
  EXPECT_FALSE(renderer.variant().direct_lights);
  const int size = 64;
  const scene::View view = scene::look_at_view({0.0f, 0.0f, 3.0f}, {0.0f, 0.0f, 0.0f},
                                               {0.0f, 1.0f, 0.0f}, glm::radians(45.0f), size, size);
  const FrameOutput out = renderer.render(s, std::span(&view, 1));
  EXPECT_EQ(out.stats.shadow_passes, 0u);  // no punctual lights: no shadow maps
  Checked c;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const scene::Ray ray = scene::view_ray(view, float(x) + 0.5f, float(y) + 0.5f);
      const float b = glm::dot(ray.origin, ray.direction);
      const float disc = b * b - (glm::dot(ray.origin, ray.origin) - kRadius * kRadius);
      if (disc <= 0.0f) continue;
      const glm::vec3 p = ray.origin + ray.direction * (-b - std::sqrt(disc));
      const float nov = glm::dot(glm::normalize(p), -ray.direction);
      if (nov < 0.2f) continue;  // silhouette pixels mix tessellated and true normals
      const glm::vec3 want = expected(nov);
      const glm::vec3 got = out.views[0].linear[std::size_t(y) * size + std::size_t(x)];
      const double err = glm::length(got - want) / glm::length(want);
      c.worst = std::max(c.worst, err);
      ++c.pixels;
      if (err > 0.02) ++c.bad;
    }
  return c;
}

class ConstantProbeTest : public GpuTest {};

TEST_F(ConstantProbeTest, DiffuseSphereReflectsAlbedoScaledRadiance) {
  const glm::vec3 albedo(0.7f, 0.5f, 0.3f);
  const float roughness = 0.9f;  // not glossy: the plan leaves the specular probe term out
  const auto& table = trace::DielectricSpecularAlbedo::get();
  const Checked c = render_and_check(device(), make_material(albedo, 0.0f, roughness), false,
                                     [&](float nov) {
                                       return albedo * (1.0f - table.directional(nov, roughness)) * kRadiance;
                                     });
  std::printf("diffuse sphere: %d pixels, worst relative error %.4f\n", c.pixels, c.worst);
  EXPECT_GT(c.pixels, 1000);
  EXPECT_EQ(c.bad, 0) << "worst relative error " << c.worst;
}

// A dielectric layer other than glTF's default (KHR_materials_ior, KHR_materials_specular): the
// diffuse base is scaled by 1 - E(n.v) of that layer, weight (E + (F0 - 0.04) dE/dF0) per
// channel, read from the tracer's table as the direct light's is.
TEST_F(ConstantProbeTest, DiffuseSphereUnderOwnDielectricLayer) {
  const glm::vec3 albedo(0.7f, 0.5f, 0.3f);
  const float roughness = 0.9f;
  scene::Material material = make_material(albedo, 0.0f, roughness);
  material.ior = 2.0f;  // F0 = 1/9 before the colour
  material.specular = 0.8f;
  material.specular_color = glm::vec3(1.0f, 0.5f, 0.25f);
  const glm::vec3 f0 = material.dielectric_f0();
  const auto& table = trace::DielectricSpecularAlbedo::get();
  const Checked c = render_and_check(device(), material, false, [&](float nov) {
    const glm::vec3 layer = material.specular * (table.directional(nov, roughness) +
                                                 (f0 - 0.04f) * table.directional_slope(nov, roughness));
    return albedo * (1.0f - layer) * kRadiance;
  });
  std::printf("diffuse sphere under an ior 2 layer: %d pixels, worst relative error %.4f\n", c.pixels,
              c.worst);
  EXPECT_GT(c.pixels, 1000);
  EXPECT_EQ(c.bad, 0) << "worst relative error " << c.worst;
}

TEST_F(ConstantProbeTest, GlossyMetalSphereReflectsSplitSum) {
  const glm::vec3 base(0.95f, 0.64f, 0.54f);
  const float roughness = 0.3f;
  const Checked c = render_and_check(device(), make_material(base, 1.0f, roughness), true,
                                     [&](float nov) {
                                       const glm::vec2 ab = integrate_dfg(nov, roughness, 128);
                                       return (base * ab.x + ab.y) * kRadiance;  // F0 = base
                                     });
  std::printf("glossy sphere: %d pixels, worst relative error %.4f\n", c.pixels, c.worst);
  EXPECT_GT(c.pixels, 1000);
  EXPECT_EQ(c.bad, 0) << "worst relative error " << c.worst;
}

}  // namespace
}  // namespace ddish::raster::test
