// The bundled Cornell box (scenes/cornell_box.gltf: an emissive ceiling panel, no punctual
// lights) rendered by the rasterizer with converged probes, against a path-traced reference of
// the same camera rendered here with trace::render_reference. All of its light is indirect
// (the panel's light reaches every wall through the probes), so this measures the probe path
// end to end: tracer -> probe volume -> fp16 textures -> trilinear SH -> shading.
//
// Measured on lavapipe (64x64, MSAA 4, L2 probes on the sidecar's 8x8x8 grid, 4 updates of
// 256 paths, reference 256 spp / 16 bounces): PSNR 23.59 dB with probes, 9.62 dB without
// (emission only); against a 1024-spp reference 23.71 dB, so reference noise is not what
// limits the figure (the 8x8x8 L2 probes' smoothing of the panel's sharp light and of the
// shadows under the blocks is; 256x256 images score higher, see the closing note).
// The thresholds leave ~1.5 dB for sampling differences between runs and devices.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "../gpu/gpu_test.h"
#include "metrics/image.h"
#include "metrics/psnr.h"
#include "probes/probe_grid.h"
#include "probes/probe_tracer.h"
#include "probes/probe_volume.h"
#include "probes/tracer_source.h"
#include "raster/renderer.h"
#include "scene/gltf_loader.h"
#include "scene/scene.h"
#include "scene/view.h"
#include "trace/reference.h"
#include "trace/tracer.h"

namespace ddish::raster::test {
namespace {

using gpu::test::GpuTest;

constexpr double kMinPsnr = 22.0;         // dB, with probes
constexpr double kMinPsnrMargin = 10.0;   // dB better than without probes

metrics::Image to_image(const ViewImage& v) {
  metrics::Image img(v.width, v.height);
  img.pixels() = v.linear.to_floats();
  return img;
}

class CornellTest : public GpuTest {};

TEST_F(CornellTest, MatchesReferenceAndBeatsNoProbes) {
  scene::Scene s = scene::load_scene(std::string(DDISH_SOURCE_DIR) + "/scenes/cornell_box.gltf");
  ASSERT_NE(s.default_camera(), nullptr);
  const int size = 64;
  const scene::View view = scene::camera_view(*s.default_camera(), size, size);

  trace::PathOptions probe_paths;
  probe_paths.max_bounces = 4;
  const trace::Tracer probe_tracer_paths(s, probe_paths);
  ASSERT_TRUE(s.sidecar.probe_counts.has_value());
  probes::ProbeVolume volume(probes::ProbeGrid(s.bounds(), *s.sidecar.probe_counts), 2);
  const probes::TracerSource source(probe_tracer_paths);
  probes::UpdateOptions update;
  update.samples = 256;
  update.seed = 7;
  const probes::ProbeTracer probe_tracer(source, update);
  for (int i = 0; i < 4; ++i) probe_tracer.update(volume);

  trace::PathOptions reference_paths;
  reference_paths.max_bounces = 16;
  const trace::Tracer reference_tracer(s, reference_paths);
  trace::ReferenceOptions ro;
  ro.spp = 256;
  const trace::ReferenceImage ref = trace::render_reference(reference_tracer, view, ro);
  metrics::Image reference(ref.width, ref.height);
  reference.pixels() = ref.pixels;

  RendererOptions with_probes;
  Renderer renderer(device(), s, volume, with_probes);
  EXPECT_FALSE(renderer.variant().direct_lights);
  EXPECT_FALSE(renderer.variant().shadows);
  const FrameOutput out = renderer.render(s, std::span(&view, 1));
  EXPECT_EQ(out.stats.shadow_passes, 0u) << "a scene without punctual lights renders no shadow maps";
  EXPECT_EQ(out.stats.forward_passes, 1u);
  EXPECT_EQ(out.stats.tonemap_passes, 1u);
  const double psnr = metrics::psnr(to_image(out.views[0]), reference);

  RendererOptions without;
  without.probes = false;
  Renderer dark(device(), s, volume, without);
  const FrameOutput out_dark = dark.render(s, std::span(&view, 1));
  const double psnr_dark = metrics::psnr(to_image(out_dark.views[0]), reference);

  std::printf("Cornell box 64x64: PSNR %.2f dB with probes, %.2f dB without (reference %d spp)\n",
              psnr, psnr_dark, ref.spp);
  EXPECT_GT(psnr, kMinPsnr);
  EXPECT_GT(psnr - psnr_dark, kMinPsnrMargin);
}

}  // namespace
}  // namespace ddish::raster::test
