// Fitted grid placement (probes/grid_placement.h): surface points uniform by area and those a
// camera sees, the visible interpolation weight against hand-computed values, the fit choosing
// the offset that the analysis says, and the light test leaving out a closed unlit box.
#include <gtest/gtest.h>

#include <cmath>

#include "../trace/trace_test_scenes.h"
#include "probes/grid_placement.h"
#include "trace/embree_scene.h"
#include "trace/texture_lookup.h"
#include "trace/tracer.h"

using namespace ddish::probes;
using ddish::scene::Aabb;
using ddish::scene::Scene;
namespace tt = ddish::trace::testing;

namespace {

// Every segment visible.
bool open_space(const glm::vec3&, const glm::vec3&) { return true; }

// A room z in [0, 1] that sees only probes inside it (a slab between two walls).
bool slab(const glm::vec3&, const glm::vec3& probe) { return probe.z >= 0.0f && probe.z <= 1.0f; }

// Points at z = (k + 0.5) / n, k < n: the slab's floor-to-ceiling line, sampled evenly.
std::vector<SurfaceSample> column(int n) {
  std::vector<SurfaceSample> points;
  for (int k = 0; k < n; ++k) points.push_back({{0.5f, 0.5f, (float(k) + 0.5f) / float(n)}, {1.0f, 0.0f, 0.0f}});
  return points;
}

// The grid of two probes along z over [-1, 3] (probes at z = 0 and 2, cells of 2 m), one along
// x and y over [0, 1].
ProbeGrid two_probes() { return ProbeGrid(Aabb{{0.0f, 0.0f, -1.0f}, {1.0f, 1.0f, 3.0f}}, {1, 1, 2}); }

}  // namespace

TEST(GridPlacement, SurfacePointsAreUniformByAreaOnTheTriangles) {
  Scene s;
  const int m = tt::add_material(s, tt::diffuse(glm::vec3(0.5f)));
  tt::add_quad(s, {0.0f, 0.0f, 0.0f}, {0.5f, 0.0f, 0.0f}, {0.0f, 0.5f, 0.0f}, m);    // area 1, z = 0, faces +z
  tt::add_quad(s, {0.0f, 0.0f, 5.0f}, {1.5f, 0.0f, 0.0f}, {0.0f, 0.5f, 0.0f}, m);    // area 3, z = 5
  const std::vector<SurfaceSample> points = sample_surfaces(s, 16384);
  ASSERT_EQ(points.size(), 16384u);
  int on_large = 0;
  for (const SurfaceSample& p : points) {
    const bool large = p.position.z == 5.0f;
    ASSERT_TRUE(large || p.position.z == 0.0f);
    on_large += large;
    const float half_width = large ? 1.5f : 0.5f;
    EXPECT_LE(std::abs(p.position.x), half_width + 1e-6f);
    EXPECT_LE(std::abs(p.position.y), 0.5f + 1e-6f);
    EXPECT_NEAR(p.normal.z, 1.0f, 1e-6f);  // single-sided: the front only
  }
  // 3/4 of the area: binomial standard deviation sqrt(0.75 * 0.25 / 16384) = 0.0034; 4.4 sigma.
  EXPECT_NEAR(double(on_large) / double(points.size()), 0.75, 0.015);
}

TEST(GridPlacement, DoubleSidedSurfacesAreSeenFromBothSides) {
  Scene s;
  ddish::scene::Material two = tt::diffuse(glm::vec3(0.5f));
  two.double_sided = true;
  tt::add_quad(s, {0.0f, 0.0f, 0.0f}, {0.5f, 0.0f, 0.0f}, {0.0f, 0.5f, 0.0f}, tt::add_material(s, two));
  const std::vector<SurfaceSample> points = sample_surfaces(s, 1000);
  int down = 0;
  for (const SurfaceSample& p : points) down += p.normal.z < 0.0f;
  EXPECT_EQ(down, 500);
}

TEST(GridPlacement, VisibleWeightIsTheTrilinearWeightOnSeenProbes) {
  const std::vector<SurfaceSample> points = column(1000);
  // In open space every point sees all its probes: the weights sum to 1.
  EXPECT_NEAR(visible_weight(two_probes(), points, open_space), 1.0, 1e-9);
  // In the slab only the probe at z = 0 is seen, with weight 1 - z / 2: the mean over z in
  // [0, 1] is 3/4 (exactly, for the evenly spaced midpoints: the weight is linear in z).
  EXPECT_NEAR(visible_weight(two_probes(), points, slab), 0.75, 1e-6);
  // Moved a quarter cell (0.5 m) up, the probes sit at 0.5 (seen) and 2.5: points below 0.5
  // clamp onto the first probe (weight 1), the rest weigh 1 - (z - 0.5) / 2 on it: 0.9375.
  EXPECT_NEAR(visible_weight(shifted_grid(two_probes(), {0.0f, 0.0f, 0.25f}), points, slab), 0.9375, 1e-6);
  // A quarter cell down: probes at -0.5 and 1.5, neither inside the slab.
  EXPECT_EQ(visible_weight(shifted_grid(two_probes(), {0.0f, 0.0f, -0.25f}), points, slab), 0.0);
  EXPECT_EQ(visible_weight(two_probes(), {}, slab), 0.0);
}

TEST(GridPlacement, TheFitMovesTheGridToWhereTheSurfacesSeeTheirProbes) {
  const std::vector<SurfaceSample> points = column(1000);
  const GridFit fit = fit_grid_placement(two_probes(), points, slab);
  // A quarter cell up puts a probe at z = 0.5 in the slab (0.9375, above); a quarter down none.
  EXPECT_EQ(fit.offset_cells, glm::vec3(0.0f, 0.0f, 0.25f));
  EXPECT_NEAR(fit.score, 0.9375, 1e-6);
  EXPECT_NEAR(fit.unmoved_score, 0.75, 1e-6);
  EXPECT_NEAR(fit.grid.position(glm::ivec3(0, 0, 0)).z, 0.5f, 1e-6f);
  EXPECT_EQ(fit.grid.counts(), two_probes().counts());
  // x and y (one probe each, the slab blind to them) were tried and left alone: 1 + 3 x 2 grids.
  EXPECT_EQ(fit.grids_scored, 7u);
  EXPECT_EQ(fit.points, 1000u);
}

TEST(GridPlacement, AGridThatIsAlreadyRightStays) {
  // In open space every offset scores 1: no gain, so the grid keeps the bounds' placement.
  const GridFit fit = fit_grid_placement(two_probes(), column(100), open_space);
  EXPECT_EQ(fit.offset_cells, glm::vec3(0.0f));
  EXPECT_EQ(fit.grid.bounds().min, two_probes().bounds().min);
  // No surface at all: nothing to score, nothing moves.
  const GridFit none = fit_grid_placement(two_probes(), {}, slab);
  EXPECT_EQ(none.offset_cells, glm::vec3(0.0f));
  EXPECT_EQ(none.grids_scored, 0u);
}

TEST(GridPlacement, SurfacesOfAClosedUnlitBoxAreNotScored) {
  // Under a sky: an open tray (a box 0.25 high without its top), whose inside the sky lights,
  // and a closed box beside it, whose inside no light reaches.
  Scene s;
  s.sidecar.environment = glm::vec3(1.0f);
  const int m = tt::add_material(s, tt::diffuse(glm::vec3(0.5f)));
  tt::add_box_inward(s, {0.0f, 0.0f, 0.0f}, {1.0f, 0.25f, 1.0f}, m, /*open_top=*/true);
  tt::add_box_inward(s, {3.0f, 0.0f, 0.0f}, {4.0f, 1.0f, 1.0f}, m);
  const std::vector<SurfaceSample> all = sample_surfaces(s, 2000);
  ddish::trace::PathOptions options;
  options.max_bounces = 4;
  const ddish::trace::Tracer tracer(s, options);
  const std::vector<SurfaceSample> lit = lit_surfaces(all, tracer, 1e-3f);
  std::size_t open_box = 0;
  for (const SurfaceSample& p : all) open_box += p.position.x <= 1.0f;
  // Every point of the tray finds the sky within 8 paths of up to 5 segments: from its floor
  // most directions leave through the top, from its walls at least half of them, so the chance
  // that all 8 paths stay inside is below 1e-8 per point. No point of the closed box does.
  EXPECT_EQ(lit.size(), open_box);
  for (const SurfaceSample& p : lit) EXPECT_LE(p.position.x, 1.0f);
  EXPECT_GT(open_box, 400u);  // a quarter of the area (2 of 8 m^2): 500 expected, sd 19
}

TEST(GridPlacement, CameraPointsAreWhatTheCamerasSeeFacingThem) {
  // A camera at the origin looking down -z at a wall at z = -2 wide enough to fill its view,
  // and the wall's back facing it (single-sided, its front toward -z): the points lie on the
  // wall with the normal turned toward the camera. Behind the camera a second wall it never sees.
  Scene s;
  const int m = tt::add_material(s, tt::diffuse(glm::vec3(0.5f)));
  tt::add_quad(s, {0.0f, 0.0f, -2.0f}, {0.0f, 10.0f, 0.0f}, {10.0f, 0.0f, 0.0f}, m);  // faces -z
  tt::add_quad(s, {0.0f, 0.0f, 3.0f}, {10.0f, 0.0f, 0.0f}, {0.0f, 10.0f, 0.0f}, m);
  ddish::scene::Camera c;
  c.yfov = 1.0f;
  s.cameras.push_back(c);
  ddish::trace::TextureSet textures(s);
  const ddish::trace::EmbreeScene embree(s, textures);
  const std::vector<SurfaceSample> points = camera_surfaces(s, embree, 500);
  ASSERT_EQ(points.size(), 500u);
  const float half_width = 2.0f * std::tan(0.5f) * (4.0f / 3.0f);  // the 4:3 view's footprint
  for (const SurfaceSample& p : points) {
    EXPECT_NEAR(p.position.z, -2.0f, 1e-4f);
    EXPECT_LE(std::abs(p.position.x), half_width + 1e-4f);
    EXPECT_NEAR(p.normal.z, 1.0f, 1e-6f);
  }
  // No camera: no points.
  s.cameras.clear();
  EXPECT_TRUE(camera_surfaces(s, embree, 500).empty());
}
