// The material sampler's anisotropy (RendererOptions::anisotropy, raster/anisotropy.h): automatic
// is off on CPU devices (lavapipe's anisotropic filter can stall a view for tens of seconds) and
// 8x elsewhere, an explicit value is clamped to the device's limit, and a value outside 0..16 is
// a clear error.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "../gpu/gpu_test.h"
#include "gpu/device.h"
#include "probes/probe_grid.h"
#include "probes/probe_volume.h"
#include "raster/anisotropy.h"
#include "raster/renderer.h"
#include "raster_scenes.h"

namespace ddish::raster::test {
namespace {

using gpu::DeviceType;
using gpu::test::GpuTest;

TEST(AnisotropyResolve, AutomaticIsOffOnCpuDevicesAndEightOnGpus) {
  EXPECT_EQ(resolve_anisotropy(0, DeviceType::cpu, true, 16.0f), 1.0f);
  EXPECT_EQ(resolve_anisotropy(0, DeviceType::discrete, true, 16.0f), 8.0f);
  EXPECT_EQ(resolve_anisotropy(0, DeviceType::integrated, true, 16.0f), 8.0f);
  EXPECT_EQ(resolve_anisotropy(0, DeviceType::integrated, true, 4.0f), 4.0f);  // the limit
}

TEST(AnisotropyResolve, ExplicitValuesAreClampedToTheDevice) {
  EXPECT_EQ(resolve_anisotropy(4, DeviceType::cpu, true, 16.0f), 4.0f);
  EXPECT_EQ(resolve_anisotropy(16, DeviceType::discrete, true, 8.0f), 8.0f);
  EXPECT_EQ(resolve_anisotropy(1, DeviceType::discrete, true, 16.0f), 1.0f);
  // Without the samplerAnisotropy feature nothing can switch it on.
  EXPECT_EQ(resolve_anisotropy(8, DeviceType::discrete, false, 16.0f), 1.0f);
}

TEST(AnisotropyResolve, ValuesOutsideTheRangeAreRejected) {
  for (int bad : {-1, 17, 1000}) {
    try {
      resolve_anisotropy(bad, DeviceType::discrete, true, 16.0f);
      FAIL() << "anisotropy " << bad << " was accepted";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("anisotropy must be 0 (automatic"), std::string::npos) << what;
      EXPECT_NE(what.find("not " + std::to_string(bad)), std::string::npos) << what;
    }
  }
}

class AnisotropyTest : public GpuTest {};

TEST_F(AnisotropyTest, RendererResolvesItForTheDevice) {
  const scene::Scene s =
      one_mesh_scene(ground_quad(1.0f), make_material({0.5f, 0.5f, 0.5f}, 0.0f, 0.5f));
  const probes::ProbeVolume volume(probes::ProbeGrid(s.bounds(), {2, 2, 2}));
  const bool feature = device().features().sampler_anisotropy;
  const float limit = device().limits().maxSamplerAnisotropy;
  const Renderer automatic(device(), s, volume, {.msaa = 1});
  if (device().info().type == DeviceType::cpu)  // lavapipe: off
    EXPECT_EQ(automatic.anisotropy(), 1.0f);
  else
    EXPECT_EQ(automatic.anisotropy(), feature ? std::min(8.0f, limit) : 1.0f);
  const Renderer four(device(), s, volume, {.msaa = 1, .anisotropy = 4});
  EXPECT_EQ(four.anisotropy(), feature ? std::min(4.0f, limit) : 1.0f);
  const Renderer off(device(), s, volume, {.msaa = 1, .anisotropy = 1});
  EXPECT_EQ(off.anisotropy(), 1.0f);
  EXPECT_THROW(Renderer(device(), s, volume, {.msaa = 1, .anisotropy = -2}), std::invalid_argument);
  EXPECT_THROW(Renderer(device(), s, volume, {.msaa = 1, .anisotropy = 32}), std::invalid_argument);
}

}  // namespace
}  // namespace ddish::raster::test
