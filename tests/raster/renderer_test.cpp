// Renderer behaviour that is not about light transport: clear errors for what a device lacks,
// the shader variants chosen from SceneFeatures, and several views in one frame (the layered
// target a later multiview path will use) giving exactly the images of separate frames.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "../gpu/gpu_test.h"
#include "gpu/buffer.h"
#include "gpu/commands.h"
#include "gpu/device.h"
#include "gpu/driver_quirks.h"
#include "gpu/error.h"
#include "gpu/transfer.h"
#include "probes/probe_grid.h"
#include "probes/probe_volume.h"
#include "raster/material_textures.h"
#include "raster/renderer.h"
#include "raster_scenes.h"
#include "scene/scene.h"
#include "sh/packing.h"
#include "scene/view.h"

namespace ddish::raster::test {
namespace {

using gpu::test::GpuTest;

class RendererTest : public GpuTest {};

scene::Scene spot_scene() {
  scene::Scene s = sphere_over_ground(0.4f);
  scene::Light spot;
  spot.name = "spot";
  spot.type = scene::LightType::Spot;
  spot.intensity = 10.0f;
  add_light(s, spot, {0.2f, 2.5f, 0.1f}, {0.0f, -1.0f, 0.0f});
  return s;
}

TEST_F(RendererTest, UnsupportedSampleCountIsAClearError) {
  scene::Scene s = spot_scene();
  const probes::ProbeVolume volume(probes::ProbeGrid(s.bounds(), {2, 2, 2}));
  // The smallest count the device lacks (lavapipe has 1 and 4, so 2).
  std::uint32_t missing = 0;
  for (std::uint32_t c : {2u, 8u, 16u, 32u, 64u})
    if ((device().info().msaa_sample_counts() & c) == 0) {
      missing = c;
      break;
    }
  ASSERT_NE(missing, 0u) << "the device has every MSAA count";
  RendererOptions options;
  options.msaa = missing;
  try {
    Renderer renderer(device(), s, volume, options);
    FAIL() << "a renderer with " << missing << "x MSAA was made";
  } catch (const gpu::GpuError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("cannot render with " + std::to_string(missing) + " samples per pixel"),
              std::string::npos) << what;
    EXPECT_NE(what.find("supports for colour and depth: 1"), std::string::npos) << what;
  }
}

TEST_F(RendererTest, FormatWithoutMipBlitsIsAClearError) {
  // A texture format the device cannot blit with linear filtering stands in for a device
  // that lacks mip generation for the formats materials use.
  gpu::CommandRunner runner(device());
  const scene::Texture texel{"t", 1, 1, {1, 2, 3, 4}};
  try {
    MaterialTextures::upload_texture(device(), runner, texel, VK_FORMAT_R8G8B8A8_SINT);
    FAIL() << "an integer texture was given linear mipmaps";
  } catch (const gpu::GpuError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot blit and linearly filter"), std::string::npos) << e.what();
  }
}

TEST_F(RendererTest, VariantFollowsSceneFeatures) {
  scene::Scene lit = spot_scene();
  const probes::ProbeVolume volume(probes::ProbeGrid(lit.bounds(), {2, 2, 2}));
  Renderer with_light(device(), lit, volume, {.msaa = 1});
  EXPECT_TRUE(with_light.variant().direct_lights);
  EXPECT_TRUE(with_light.variant().shadows);
  EXPECT_TRUE(with_light.variant().specular_probes);  // the ground's roughness is 0.4
  EXPECT_FALSE(with_light.variant().textures);
  EXPECT_FALSE(with_light.variant().emission);

  scene::Scene matte = one_mesh_scene(ground_quad(1.0f), make_material({0.5f, 0.5f, 0.5f}, 0.0f, 1.0f));
  Renderer no_light(device(), matte, volume, {.msaa = 1});
  EXPECT_FALSE(no_light.variant().direct_lights);
  EXPECT_FALSE(no_light.variant().shadows);
  EXPECT_FALSE(no_light.variant().specular_probes);
}

TEST_F(RendererTest, SampleShadingRendersWhereSupported) {
  if (!device().features().sample_rate_shading) {
    // Then asking for it must be refused by name.
    scene::Scene s = spot_scene();
    const probes::ProbeVolume volume(probes::ProbeGrid(s.bounds(), {2, 2, 2}));
    EXPECT_THROW(Renderer(device(), s, volume, {.msaa = 4, .sample_shading = true}), gpu::GpuError);
    return;
  }
  scene::Scene s = spot_scene();
  const probes::ProbeVolume volume(probes::ProbeGrid(s.bounds(), {2, 2, 2}));
  Renderer renderer(device(), s, volume, {.msaa = 4, .sample_shading = true});
  const scene::View view = scene::look_at_view({0, 3, 3}, {0, 0, 0}, {0, 1, 0}, 0.8f, 32, 32);
  const FrameOutput out = renderer.render(s, std::span(&view, 1));
  EXPECT_EQ(out.views[0].linear.size(), 32u * 32u);
  EXPECT_EQ(out.stats.shadow_passes, 1u);
}

TEST_F(RendererTest, SeveralViewsEqualSeparateFrames) {
  scene::Scene s = spot_scene();
  const probes::ProbeVolume volume(probes::ProbeGrid(s.bounds(), {2, 2, 2}));
  Renderer renderer(device(), s, volume, {.msaa = 4});
  const std::vector<scene::View> views{
      scene::look_at_view({0, 3, 3}, {0, 0, 0}, {0, 1, 0}, 0.8f, 48, 32),
      scene::look_at_view({1, 2, 3}, {0, 0.5f, 0}, {0, 1, 0}, 0.9f, 48, 32)};
  const FrameOutput both = renderer.render(s, views);
  ASSERT_EQ(both.views.size(), 2u);
  EXPECT_EQ(both.stats.forward_passes, 2u);
  EXPECT_EQ(both.stats.shadow_passes, 1u);  // shadow maps are per frame, not per view
  for (std::size_t v = 0; v < views.size(); ++v) {
    const FrameOutput one = renderer.render(s, std::span(&views[v], 1));
    EXPECT_EQ(one.views[0].linear, both.views[v].linear) << "view " << v;
    EXPECT_EQ(one.views[0].display, both.views[v].display) << "view " << v;
  }
  EXPECT_NE(both.views[0].linear, both.views[1].linear);
}

TEST_F(RendererTest, BatchesOfViewsEqualOneSubmission) {
  // Views drawn a few at a time into a reused target (RendererOptions::batch_views) give the
  // images of one submission of all views; the shadow maps are drawn once for the frame.
  scene::Scene s = spot_scene();
  const probes::ProbeVolume volume(probes::ProbeGrid(s.bounds(), {2, 2, 2}));
  std::vector<scene::View> views;
  for (int i = 0; i < 10; ++i)
    views.push_back(scene::look_at_view({-1.0f + 0.2f * float(i), 2.5f, 3.0f}, {0, 0.3f, 0}, {0, 1, 0},
                                        0.8f, 24, 20));
  std::vector<ViewMethod> methods{ViewMethod::per_view};
  // Mesa 22's lavapipe puts a clipped primitive into its pass's first view (gpu/driver_quirks.h),
  // and which view is first depends on the batching: its multiview frames cannot be compared so.
  if (device().features().multiview &&
      gpu::multiview_defect(device().info()) != gpu::MultiviewDefect::clipped_primitives_lose_view)
    methods.push_back(ViewMethod::multiview);
  for (ViewMethod method : methods) {
    Renderer whole(device(), s, volume, {.msaa = 4, .view_method = method, .batch_views = 10});
    Renderer batched(device(), s, volume, {.msaa = 4, .view_method = method, .batch_views = 8});
    EXPECT_EQ(batched.batch_size(24, 20, 10), 8u);
    const FrameOutput one = whole.render(s, views);
    const FrameOutput two = batched.render(s, views);
    ASSERT_EQ(two.views.size(), views.size());
    EXPECT_EQ(two.stats.shadow_passes, one.stats.shadow_passes) << to_string(method);
    EXPECT_EQ(two.stats.shadow_passes, 1u) << to_string(method);
    EXPECT_EQ(two.stats.tonemap_passes, 2u) << to_string(method);
    EXPECT_EQ(one.stats.tonemap_passes, 1u) << to_string(method);
    for (std::size_t v = 0; v < views.size(); ++v) {
      EXPECT_EQ(two.views[v].linear, one.views[v].linear) << to_string(method) << ", view " << v;
      EXPECT_EQ(two.views[v].display, one.views[v].display) << to_string(method) << ", view " << v;
    }
  }
  // The automatic batch keeps a frame's target within RendererOptions::kBatchTargetBytes.
  Renderer automatic(device(), s, volume, {.msaa = 4});
  EXPECT_EQ(automatic.batch_size(24, 20, 10), 10u);
  const std::uint32_t big = automatic.batch_size(1024, 910, 72);
  EXPECT_GE(big, 1u);
  // Per sample: depth, colour (unless the visibility pass shades the resolve image, which it
  // does where no BLEND material follows) and the visibility pass's ids (8 bytes) when it shades.
  const bool visibility = automatic.shading_pass() == ShadingPass::visibility;
  const std::uint64_t sample = 4 + (visibility && !automatic.plan().alpha_blend ? 0 : 8) + (visibility ? 8 : 0);
  EXPECT_LE(std::uint64_t{big} * 1024 * 910 * (4 * sample + 20), RendererOptions::kBatchTargetBytes);
  EXPECT_GT(std::uint64_t{big + 1} * 1024 * 910 * (4 * sample + 20), RendererOptions::kBatchTargetBytes);
}

TEST_F(RendererTest, AfterBatchCommandsSeeEveryViewOnTheGpu) {
  // A RenderRequest's after_batch (the window's and OpenXR's way to take the views) copies each
  // batch out of the renderer's buffers; the copies equal the read-back images bit for bit,
  // though the batches reuse one target, and with read_back off nothing comes to the CPU.
  scene::Scene s = spot_scene();
  const probes::ProbeVolume volume(probes::ProbeGrid(s.bounds(), {2, 2, 2}));
  std::vector<scene::View> views;
  for (int i = 0; i < 7; ++i)
    views.push_back(scene::look_at_view({-0.9f + 0.3f * float(i), 2.5f, 3.0f}, {0, 0.3f, 0},
                                        {0, 1, 0}, 0.8f, 20, 16));
  Renderer renderer(device(), s, volume, {.msaa = 4, .batch_views = 3});
  const FrameOutput read = renderer.render(s, views);

  const VkDeviceSize per_view = 20 * 16;
  gpu::Buffer display(device(), per_view * 4 * views.size(), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                      gpu::MemoryUse::readback);
  gpu::Buffer hdr(device(), per_view * 8 * views.size(), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                  gpu::MemoryUse::readback);
  std::vector<std::uint32_t> batches;
  RenderRequest request;
  request.read_back = false;
  request.after_batch = [&](VkCommandBuffer cmd, const BatchViews& batch) {
    batches.push_back(batch.first_view);
    EXPECT_EQ(batch.width, 20u);
    EXPECT_EQ(batch.height, 16u);
    gpu::copy_buffer(cmd, batch.display, display, batch.display_offset(batch.count), 0,
                     batch.display_offset(batch.first_view));
    gpu::copy_buffer(cmd, batch.hdr, hdr, batch.hdr_offset(batch.count), 0,
                     batch.hdr_offset(batch.first_view));
    gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                        VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
  };
  const FrameOutput kept = renderer.render(s, views, request);
  EXPECT_EQ(batches, (std::vector<std::uint32_t>{0, 3, 6}));
  ASSERT_EQ(kept.views.size(), views.size());
  const auto* pixels = static_cast<const std::uint32_t*>(display.mapped());
  const auto* halves = static_cast<const std::uint16_t*>(hdr.mapped());
  for (std::size_t v = 0; v < views.size(); ++v) {
    EXPECT_EQ(kept.views[v].width, 20);
    EXPECT_EQ(kept.views[v].height, 16);
    EXPECT_TRUE(kept.views[v].display.empty());
    EXPECT_TRUE(kept.views[v].linear.empty());
    const std::vector<std::uint32_t> copied(pixels + per_view * v, pixels + per_view * (v + 1));
    EXPECT_EQ(copied, read.views[v].display) << "view " << v;
    for (std::size_t i = 0; i < per_view; ++i)
      ASSERT_EQ(sh::half_to_float(halves[(per_view * v + i) * 4]), read.views[v].linear[i].x)
          << "view " << v << ", pixel " << i;
  }
  EXPECT_GT(kept.stats.tonemap_passes, 0u);
  EXPECT_EQ(kept.stats.readback_ms, 0.0);

  // Display pixels only (a run that writes no EXR): the same display pixels, no linear ones.
  RenderRequest display_only;
  display_only.linear = false;
  const FrameOutput shown = renderer.render(s, views, display_only);
  ASSERT_EQ(shown.views.size(), views.size());
  for (std::size_t v = 0; v < views.size(); ++v) {
    EXPECT_TRUE(shown.views[v].linear.empty()) << "view " << v;
    EXPECT_EQ(shown.views[v].display, read.views[v].display) << "view " << v;
  }
}

TEST_F(RendererTest, StaticShadowMapsAreKept) {
  scene::Scene s = spot_scene();
  const probes::ProbeVolume volume(probes::ProbeGrid(s.bounds(), {2, 2, 2}));
  Renderer renderer(device(), s, volume, {.msaa = 1});
  const scene::View view = scene::look_at_view({0, 3, 3}, {0, 0, 0}, {0, 1, 0}, 0.8f, 32, 32);
  const FrameOutput first = renderer.render(s, std::span(&view, 1));
  const FrameOutput second = renderer.render(s, std::span(&view, 1));
  EXPECT_EQ(first.stats.shadow_passes, 1u);
  EXPECT_FALSE(first.stats.shadows_reused);
  EXPECT_EQ(second.stats.shadow_passes, 0u);
  EXPECT_TRUE(second.stats.shadows_reused);
  EXPECT_EQ(first.views[0].linear, second.views[0].linear);
  // Moving the sphere invalidates the maps, and the new shadow shows.
  s.nodes[1].translation.x += 0.5f;
  s.pose(s.time);
  const FrameOutput moved = renderer.render(s, std::span(&view, 1));
  EXPECT_EQ(moved.stats.shadow_passes, 1u);
  EXPECT_NE(moved.views[0].linear, second.views[0].linear);
}

// A masked quad between a spot light and the ground: with alpha below its cutoff it casts no
// shadow (the masked shadow pipeline discards it), above the cutoff it does.
TEST_F(RendererTest, MaskedCastersCutTheirShadows) {
  auto centre_radiance = [&](std::optional<float> occluder_alpha) {
    scene::Scene s = one_mesh_scene(ground_quad(2.0f), make_material({0.6f, 0.6f, 0.6f}, 0.0f, 0.8f));
    if (occluder_alpha) {
      scene::Material leaf = make_material({0.2f, 0.6f, 0.2f}, 0.0f, 0.8f);
      leaf.base_color.a = *occluder_alpha;
      leaf.alpha_mode = scene::AlphaMode::Mask;
      leaf.alpha_cutoff = 0.5f;
      leaf.double_sided = true;
      add_instance(s, ground_quad(0.4f), leaf, {0.0f, 1.0f, 0.0f});
    }
    scene::Light spot;
    spot.name = "spot";
    spot.type = scene::LightType::Spot;
    spot.intensity = 10.0f;
    add_light(s, spot, {0.0f, 2.5f, 0.0f}, {0.0f, -1.0f, 0.0f});
    const probes::ProbeVolume volume(probes::ProbeGrid(s.bounds(), {2, 2, 2}));
    Renderer renderer(device(), s, volume, {.msaa = 1, .probes = false});
    // The view ray through the centre of the 33x33 image hits the ground at the origin.
    const scene::View view = scene::look_at_view({0, 3.5f, 3.5f}, {0, 0, 0}, {0, 1, 0}, 0.8f, 33, 33);
    const FrameOutput out = renderer.render(s, std::span(&view, 1));
    return out.views[0].linear[16 * 33 + 16];
  };
  const glm::vec3 open = centre_radiance(std::nullopt);
  const glm::vec3 cut = centre_radiance(0.3f);
  const glm::vec3 solid = centre_radiance(0.9f);
  ASSERT_GT(open.g, 0.1f);
  EXPECT_NEAR(cut.g, open.g, 0.01f * open.g) << "a cut-out caster still shadows";
  EXPECT_LT(solid.g, 0.05f * open.g) << "a kept caster casts no shadow";
}

}  // namespace
}  // namespace ddish::raster::test
