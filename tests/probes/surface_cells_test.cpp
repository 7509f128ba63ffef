// Classification's second phase (probes/surface_cells.h): probes whose neighbouring cells hold no
// surface are left out. The triangle-box test on analytic cases, a scene built in memory where
// each probe's fate is known, and the bundled animated Cornell box, whose moving block must keep
// every probe it passes.
#include <gtest/gtest.h>

#include <algorithm>

#include "probes/surface_cells.h"
#include "scene/gltf_loader.h"
#include "scene/scene.h"

using namespace ddish::probes;
using ddish::scene::Aabb;
using ddish::scene::Scene;

namespace {

const glm::vec3 kLo(0.0f), kHi(1.0f);

// One quad (two triangles) as a mesh and an instance at the identity.
void add_quad(Scene& s, const std::array<glm::vec3, 4>& q) {
  ddish::scene::Mesh mesh;
  for (const glm::vec3& p : q) {
    mesh.positions.push_back(p);
    mesh.normals.emplace_back(0.0f, 0.0f, 1.0f);
    mesh.bounds.expand(p);
  }
  mesh.indices = {0, 1, 2, 0, 2, 3};
  s.meshes.push_back(mesh);
  ddish::scene::Instance inst;
  inst.mesh = int(s.meshes.size()) - 1;
  s.instances.push_back(inst);
}

}  // namespace

TEST(TriangleBox, InsideOutsideAndTouching) {
  EXPECT_TRUE(triangle_overlaps_box({0.2f, 0.2f, 0.5f}, {0.8f, 0.2f, 0.5f}, {0.5f, 0.8f, 0.5f}, kLo, kHi));
  EXPECT_FALSE(triangle_overlaps_box({2.0f, 2.0f, 2.0f}, {3.0f, 2.0f, 2.0f}, {2.0f, 3.0f, 2.0f}, kLo, kHi));
  // A box face touched by a triangle lying in its plane counts.
  EXPECT_TRUE(triangle_overlaps_box({0.2f, 0.2f, 1.0f}, {0.8f, 0.2f, 1.0f}, {0.5f, 0.8f, 1.0f}, kLo, kHi));
  // A large triangle that contains the box's cross-section while no vertex is inside it.
  EXPECT_TRUE(triangle_overlaps_box({-10.0f, -10.0f, 0.5f}, {10.0f, -10.0f, 0.5f}, {0.0f, 10.0f, 0.5f}, kLo, kHi));
}

TEST(TriangleBox, ThePlaneAxisSeparatesACornerMiss) {
  // The plane x + y + z = 3.3 passes beyond the corner (1, 1, 1) (where x + y + z = 3), while
  // the triangle's bounding box overlaps the box: only the normal axis separates them.
  const glm::vec3 a(1.1f, 1.1f, 1.1f), b(0.9f, 1.3f, 1.1f), c(1.3f, 1.1f, 0.9f);
  ASSERT_LT(std::min({a.x, b.x, c.x}), 1.0f);
  EXPECT_FALSE(triangle_overlaps_box(a, b, c, kLo, kHi));
  EXPECT_TRUE(triangle_overlaps_box(a - 0.2f, b - 0.2f, c - 0.2f, kLo, kHi));  // x + y + z = 2.7
}

TEST(TriangleBox, AnEdgeAxisSeparatesASkewMiss) {
  // A thin sliver along the diagonal x = y in the plane z = 0.5, shifted so that its edge runs
  // past the box's corner (1, 0) on the outside: the boxes overlap, the planes cross, only an
  // edge-cross-axis separates.
  const glm::vec3 a(0.9f, -0.5f, 0.5f), b(2.0f, 0.6f, 0.5f), c(2.0f, 0.55f, 0.5f);
  EXPECT_FALSE(triangle_overlaps_box(a, b, c, kLo, kHi));
  // Shifted by 0.5 along -x, the sliver covers y in [0.073, 0.1] at x = 1, inside the box.
  EXPECT_TRUE(triangle_overlaps_box(a - glm::vec3(0.5f, 0, 0), b - glm::vec3(0.5f, 0, 0),
                                    c - glm::vec3(0.5f, 0, 0), kLo, kHi));
}

TEST(SurfaceCells, AProbeInAnEmptyCellIsLeftOutAndProbesNearTheSurfaceStay) {
  // A 5 x 5 x 5 grid over [0, 4]^3 (probes at integer points, cells of 1 m) and a small quad in
  // the cell (0..1)^3 at z = 0.4: the cells that reach it grown by half a cell are cells 0 and 1
  // along x and y (cell 1 spans [0.5, 2.5]) and cell 0 alone along z ([-0.5, 1.5]), so
  // the probes kept are those at x, y <= 2 and z <= 1; probe (4, 4, 4) is left out.
  Scene s;
  add_quad(s, {glm::vec3(0.2f, 0.2f, 0.4f), {0.8f, 0.2f, 0.4f}, {0.8f, 0.8f, 0.4f}, {0.2f, 0.8f, 0.4f}});
  // Probe (x, y, z) at the integer point: bounds inset by half a cell, as ProbeGrid places them.
  const ProbeGrid grid(Aabb{glm::vec3(-0.5f), glm::vec3(4.5f)}, glm::ivec3(5));
  ASSERT_EQ(grid.position(glm::ivec3(1, 2, 3)), glm::vec3(1.0f, 2.0f, 3.0f));
  const std::vector<bool> near = probes_near_surfaces(grid, s);
  for (std::uint32_t i = 0; i < grid.probe_count(); ++i) {
    const glm::ivec3 p = grid.cell(i);
    EXPECT_EQ(near[i], p.x <= 2 && p.y <= 2 && p.z <= 1) << p.x << "," << p.y << "," << p.z;
  }

  ProbeVolume volume(grid);
  EXPECT_EQ(leave_out_probes(volume, near), 125u - 18u);
  EXPECT_EQ(volume.active_count(), 18u);
  EXPECT_EQ(volume.inside_geometry_count(), 0u);
  const std::uint32_t far = grid.index(glm::ivec3(4, 4, 4));
  EXPECT_FALSE(volume.state(far).active());
  EXPECT_TRUE(volume.state(grid.index(glm::ivec3(0, 0, 0))).active());
}

TEST(SurfaceCells, GeometryOutsideTheGridKeepsTheBorderProbesThatLightIt) {
  // A floor below the grid: the shader clamps its points onto the bottom layer of cells, so the
  // two bottom layers of probes light it and stay; everything above is left out.
  Scene s;
  add_quad(s, {glm::vec3(-10.0f, -10.0f, -3.0f), {10.0f, -10.0f, -3.0f}, {10.0f, 10.0f, -3.0f}, {-10.0f, 10.0f, -3.0f}});
  const ProbeGrid grid(Aabb{glm::vec3(-0.5f), glm::vec3(4.5f)}, glm::ivec3(5));
  const std::vector<bool> near = probes_near_surfaces(grid, s);
  for (std::uint32_t i = 0; i < grid.probe_count(); ++i) EXPECT_EQ(near[i], grid.cell(i).z <= 1) << i;
}

TEST(SurfaceCells, AMovingInstanceKeepsEveryProbeItsPathNeeds) {
  // The animated Cornell box (its block slides for 4 s): every probe that a still scene posed at
  // any time of the animation would need is kept, and the scene is posed back where it was.
  Scene s = ddish::scene::load_scene(std::string(DDISH_SOURCE_DIR) + "/scenes/cornell_animated.gltf");
  ASSERT_FALSE(s.animations.empty());
  s.pose(1.25);
  const ProbeGrid grid(s.bounds(), glm::ivec3(8));
  const std::vector<bool> near = probes_near_surfaces(grid, s);
  EXPECT_EQ(s.time, 1.25);
  std::size_t still_total = 0;
  for (double t : {0.0, 1.0, 2.0, 2.5, 3.0, 4.0}) {
    Scene still = s;
    still.pose(t);
    still.animations.clear();
    const std::vector<bool> at_t = probes_near_surfaces(grid, still);
    for (std::uint32_t i = 0; i < grid.probe_count(); ++i) EXPECT_TRUE(near[i] || !at_t[i]) << "probe " << i << " at t = " << t;
    still_total = std::max<std::size_t>(still_total, std::size_t(std::count(at_t.begin(), at_t.end(), true)));
  }
  // The closed box has empty cells in its middle, so the phase leaves some probes out.
  EXPECT_LT(std::count(near.begin(), near.end(), true), std::ptrdiff_t(grid.probe_count()));
  EXPECT_GE(std::size_t(std::count(near.begin(), near.end(), true)), still_total);
}
