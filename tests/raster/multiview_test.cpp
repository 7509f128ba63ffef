// Multi-view recording and cluster culling (raster/view_method.h, raster/draw_list.h):
// - layered passes (gl_Layer) give the images of one pass per view, within one fp16 step, for a
//   light-field rig of the Cornell box whose side views see the box partly outside their frusta
//   and for views inside the box whose walls cross the near plane; multiview passes (blocks of
//   maxMultiviewViewCount views, gl_ViewIndex) do too except on lavapipe 22, whose multiview
//   loses clipped primitives to the pass's first view (see clipped_primitives_lose_view below),
//   and they are exact there as well while no primitive is clipped; on lavapipe 25 they run with
//   the forward pass's view-mask reset (gpu/driver_quirks.h), without which they crashed;
// - culling never changes an image, and it does drop clusters a view cannot see.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "../gpu/gpu_test.h"
#include "gpu/device.h"
#include "gpu/driver_quirks.h"
#include "probes/probe_grid.h"
#include "probes/probe_volume.h"
#include "raster/renderer.h"
#include "raster_scenes.h"
#include "scene/gltf_loader.h"
#include "scene/scene.h"
#include "scene/view.h"
#include "sh/sh_rgb.h"
#include "view_rigs.h"

namespace ddish::raster::test {
namespace {

using gpu::test::GpuTest;

class MultiviewTest : public GpuTest {};

// Probes whose light varies across the volume and with direction, so that every view's
// shading (and the view index the fragment stage reads its eye from) shows in the pixels.
probes::ProbeVolume varied_volume(const scene::Scene& s) {
  probes::ProbeVolume volume(probes::ProbeGrid(s.bounds(), {3, 3, 3}), 2);
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i) {
    sh::ShRgb sh(2);
    sh[0] = glm::vec3(1.0f + 0.1f * float(i % 5), 1.2f, 0.8f + 0.05f * float(i % 3));
    sh[1] = glm::vec3(0.3f, -0.2f, 0.1f);
    sh[2] = glm::vec3(-0.1f, 0.25f, 0.2f);
    sh[3] = glm::vec3(0.2f, 0.1f, -0.3f);
    volume.set_sh(i, sh);
  }
  return volume;
}

scene::Scene cornell() {
  return scene::load_scene(std::string(DDISH_SOURCE_DIR) + "/scenes/cornell_box.gltf");
}

// 8 rig views (the outer ones see the box partly outside their frusta) and 2 views from
// inside the box, whose walls cross the near plane and the frustum sides.
std::vector<scene::View> cornell_views(const scene::Scene& s, int width, int height) {
  const scene::Camera& camera = *s.default_camera();
  const float focal = glm::length(s.bounds().center() - camera.eye);
  std::vector<scene::View> views = rig_views(camera, 8, 1.2f * focal, focal, width, height);
  const glm::vec3 c = s.bounds().center();
  const glm::vec3 e = s.bounds().extent();
  views.push_back(scene::look_at_view(c + glm::vec3(0.3f * e.x, 0.0f, 0.3f * e.z), c - glm::vec3(e.x, 0, 0),
                                      {0, 1, 0}, 1.4f, width, height, 0.05f * e.x, 100.0f));
  views.push_back(scene::look_at_view(c, c + glm::vec3(0, -e.y, 0.3f * e.z), {0, 0, 1}, 1.2f, width,
                                      height, 0.2f * e.y, 100.0f));
  return views;
}

// Whether two images agree within one fp16 step per channel.
void expect_within_one_step(const ViewImage& a, const ViewImage& b, const std::string& what) {
  ASSERT_EQ(a.linear.size(), b.linear.size()) << what;
  int bad = 0;
  double worst = 0.0;
  for (std::size_t i = 0; i < a.linear.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const float x = a.linear[i][c], y = b.linear[i][c];
      const float big = std::max(std::abs(x), std::abs(y));
      const float step = big > 6.1e-5f ? std::exp2(std::floor(std::log2(big)) - 10.0f) : 6e-8f;
      const double d = std::abs(double(x) - double(y));
      worst = std::max(worst, d / step);
      if (d > step * 1.0001) ++bad;
    }
  EXPECT_EQ(bad, 0) << what << ": channels more than one fp16 step apart (worst " << worst << " steps)";
}

FrameOutput render_with(gpu::Device& device, const scene::Scene& s, const probes::ProbeVolume& volume,
                        std::span<const scene::View> views, ViewMethod method, bool cull) {
  RendererOptions o;
  o.msaa = 4;
  o.view_method = method;
  o.cull = cull;
  // The forward pass's recording is what these tests pin (the visibility pass records its
  // geometry per view or layered: visibility_pass_test.cpp).
  o.shading_pass = ShadingPass::forward;
  Renderer renderer(device, s, volume, o);
  return renderer.render(s, views);
}

// lavapipe of Mesa 22 drops the view index of every primitive its clipper cuts (near plane, or
// beyond the guard band): such a primitive of view k lands in the pass's first view, so
// multiview frames differ from per-view ones wherever big triangles reach out of a frustum
// (gpu/driver_quirks.h). Found by LayeredAndMultiviewEqualPerViewPasses: views of the Cornell
// box from outside had parts of views 1 and 2 drawn into view 0 (a debug colour of the view
// index showed it); layered passes, whose gl_Layer survives clipping, are exact.
bool clipped_primitives_lose_view(const gpu::Device& device) {
  return gpu::multiview_defect(device.info()) == gpu::MultiviewDefect::clipped_primitives_lose_view;
}

TEST_F(MultiviewTest, LayeredAndMultiviewEqualPerViewPasses) {
  const scene::Scene s = cornell();
  ASSERT_NE(s.default_camera(), nullptr);
  const probes::ProbeVolume volume = varied_volume(s);
  const std::vector<scene::View> views = cornell_views(s, 48, 40);
  const FrameOutput reference = render_with(device(), s, volume, views, ViewMethod::per_view, false);
  EXPECT_EQ(reference.stats.forward_passes, views.size());
  // The views differ (each view really reads its own matrix and eye).
  EXPECT_NE(reference.views[0].linear, reference.views[7].linear);

  if (device().features().shader_output_layer)
    for (bool cull : {false, true}) {
      const FrameOutput out = render_with(device(), s, volume, views, ViewMethod::layered, cull);
      ASSERT_EQ(out.views.size(), views.size());
      EXPECT_EQ(out.stats.forward_passes, 1u);
      for (std::size_t v = 0; v < views.size(); ++v)
        expect_within_one_step(out.views[v], reference.views[v],
                               std::string("layered") + (cull ? " culled" : "") + ", view " + std::to_string(v));
    }

  const FrameOutput multi = render_with(device(), s, volume, views, ViewMethod::multiview, true);
  const std::uint32_t per_pass = std::max(1u, device().info().max_multiview_view_count);
  EXPECT_EQ(multi.stats.forward_passes, (views.size() + per_pass - 1) / per_pass);
  if (clipped_primitives_lose_view(device())) {
    // A canary: when a Mesa update fixes the bug, multiview deserves a new measurement.
    bool differs = false;
    for (std::size_t v = 0; v < views.size(); ++v) differs |= multi.views[v].linear != reference.views[v].linear;
    EXPECT_TRUE(differs) << "lavapipe 22's multiview clipping bug is gone: re-measure ViewMethod::multiview";
  } else {
    for (std::size_t v = 0; v < views.size(); ++v)
      expect_within_one_step(multi.views[v], reference.views[v], "multiview, view " + std::to_string(v));
  }
}

TEST_F(MultiviewTest, MultiviewEqualsPerViewPassesWhenNothingIsClipped) {
  // Small triangles wholly inside every view's frustum (a sphere seen by a rig of 9 views: a
  // block of 6 and a block of 3 on lavapipe) never reach the clipper, so multiview is exact
  // on every device, lavapipe 22 included.
  scene::Scene s = one_mesh_scene(uv_sphere(1.0f, 64, 32), make_material({0.8f, 0.6f, 0.4f}, 0.0f, 0.4f));
  add_instance(s, uv_sphere(0.4f, 32, 16), make_material({0.2f, 0.5f, 0.8f}, 0.0f, 0.7f), {1.2f, 0.6f, 0.8f});
  const probes::ProbeVolume volume = varied_volume(s);
  scene::Camera camera;
  camera.eye = {0.3f, 0.2f, 6.0f};
  camera.yfov = 0.7f;
  const std::vector<scene::View> views = rig_views(camera, 9, 2.0f, 6.0f, 40, 40);
  const FrameOutput reference = render_with(device(), s, volume, views, ViewMethod::per_view, false);
  for (bool cull : {false, true}) {
    const FrameOutput multi = render_with(device(), s, volume, views, ViewMethod::multiview, cull);
    for (std::size_t v = 0; v < views.size(); ++v)
      expect_within_one_step(multi.views[v], reference.views[v],
                             std::string("multiview") + (cull ? " culled" : "") + ", view " + std::to_string(v));
  }
}

TEST_F(MultiviewTest, CullingNeverChangesTheImage) {
  // The Cornell box and a finely tessellated sphere in it, seen by the rig: culling must only
  // remove what no pixel shows, so culled and unculled frames are identical bit for bit.
  scene::Scene s = cornell();
  const glm::vec3 c = s.bounds().center();
  add_instance(s, uv_sphere(0.15f * s.bounds().extent().x, 96, 48),
               make_material({0.7f, 0.5f, 0.3f}, 0.0f, 0.5f), c);
  const probes::ProbeVolume volume = varied_volume(s);
  const std::vector<scene::View> views = cornell_views(s, 40, 32);
  std::vector<ViewMethod> methods{ViewMethod::per_view};
  if (device().features().shader_output_layer) methods.push_back(ViewMethod::layered);
  for (ViewMethod method : methods) {
    const FrameOutput all = render_with(device(), s, volume, views, method, false);
    const FrameOutput culled = render_with(device(), s, volume, views, method, true);
    EXPECT_LT(culled.stats.cull.triangles_drawn, all.stats.cull.triangles_drawn);
    for (std::size_t v = 0; v < views.size(); ++v) {
      EXPECT_EQ(culled.views[v].linear, all.views[v].linear) << to_string(method) << ", view " << v;
      EXPECT_EQ(culled.views[v].display, all.views[v].display) << to_string(method) << ", view " << v;
    }
  }
}

TEST_F(MultiviewTest, CullingDropsClustersAViewCannotSee) {
  // A sphere of 32768 triangles (64 clusters): a view of its side from close by sees a part of
  // the front half; cones drop the back half, the frustum most of the front.
  scene::Scene s = one_mesh_scene(uv_sphere(1.0f, 256, 64), make_material({0.8f, 0.8f, 0.8f}, 0.0f, 0.5f));
  const probes::ProbeVolume volume = varied_volume(s);
  const scene::View whole = scene::look_at_view({0, 0, 6}, {0, 0, 0}, {0, 1, 0}, 0.6f, 32, 32);
  const scene::View part = scene::look_at_view({0.9f, 0.0f, 1.6f}, {0.9f, 0.0f, 0.0f}, {0, 1, 0}, 0.4f, 32, 32);
  const std::vector<scene::View> views{whole, part};
  const FrameOutput culled = render_with(device(), s, volume, views, ViewMethod::per_view, true);
  const FrameOutput all = render_with(device(), s, volume, views, ViewMethod::per_view, false);
  const CullStats& c = culled.stats.cull;
  EXPECT_EQ(c.clusters_tested, 2u * 64u);
  EXPECT_EQ(all.stats.cull.clusters_drawn, 2u * 64u);
  EXPECT_LT(c.clusters_drawn, 64u + 20u) << "the whole view keeps its front half, the part view little";
  EXPECT_GT(c.clusters_drawn, 32u);
  // Each view alone, to see the close view's share.
  const FrameOutput part_only = render_with(device(), s, volume, std::span(&views[1], 1), ViewMethod::per_view, true);
  EXPECT_LT(part_only.stats.cull.clusters_drawn, 20u);
  EXPECT_GT(part_only.stats.cull.clusters_drawn, 0u);
  EXPECT_LT(part_only.stats.cull.triangles_drawn, all.stats.cull.triangles_drawn / 2 / 3);
  for (std::size_t v = 0; v < views.size(); ++v) EXPECT_EQ(culled.views[v].linear, all.views[v].linear);
}

}  // namespace
}  // namespace ddish::raster::test
