// Volume layout: index <-> cell <-> position, spacing fitting, and the grid coordinate mapping.
#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

#include "probes/probe_grid.h"

using ddish::probes::ProbeGrid;
using ddish::scene::Aabb;

TEST(ProbeGrid, IndexCellPositionRoundTrip) {
  ProbeGrid grid(Aabb{{-2.0f, 0.0f, 1.0f}, {6.0f, 3.0f, 5.0f}}, {4, 3, 5});
  ASSERT_EQ(grid.probe_count(), 60u);
  EXPECT_EQ(grid.spacing(), glm::vec3(2.0f, 1.0f, 0.8f));
  for (std::uint32_t i = 0; i < grid.probe_count(); ++i) {
    glm::ivec3 c = grid.cell(i);
    ASSERT_TRUE(grid.contains(c));
    ASSERT_EQ(grid.index(c), i);
    glm::vec3 g = grid.grid_coordinate(grid.position(i));
    for (int a = 0; a < 3; ++a) ASSERT_NEAR(g[a], float(c[a]), 1e-5f);
  }
  // x fastest, then y, then z.
  EXPECT_EQ(grid.index({1, 0, 0}), 1u);
  EXPECT_EQ(grid.index({0, 1, 0}), 4u);
  EXPECT_EQ(grid.index({0, 0, 1}), 12u);
  // Inset by half a cell from the bounds.
  EXPECT_EQ(grid.position(glm::ivec3(0)), glm::vec3(-1.0f, 0.5f, 1.4f));
  glm::vec3 last = grid.position(glm::ivec3(3, 2, 4));
  EXPECT_NEAR(last.x, 5.0f, 1e-6f);
  EXPECT_NEAR(last.y, 2.5f, 1e-6f);
  EXPECT_NEAR(last.z, 4.6f, 1e-6f);
}

TEST(ProbeGrid, SpacingFitCoversBounds) {
  Aabb bounds{{-10.0f, -1.0f, 0.0f}, {13.5f, 4.0f, 0.3f}};
  for (float target : {0.25f, 0.7f, 1.0f, 3.0f, 100.0f}) {
    ProbeGrid grid = ProbeGrid::fit_spacing(bounds, target);
    for (int a = 0; a < 3; ++a) {
      float extent = bounds.extent()[a];
      int n = grid.counts()[a];
      ASSERT_GE(n, 1);
      // The actual spacing never exceeds the target, and one probe fewer would.
      EXPECT_LE(grid.spacing()[a], target * (1.0f + 1e-6f)) << "axis " << a;
      if (n > 1) {
        EXPECT_GT(extent / float(n - 1), target) << "axis " << a;
      }
      // The probes' cells tile the bounds exactly: first and last probe half a cell inside.
      glm::ivec3 lo(0), hi = grid.counts() - 1;
      EXPECT_NEAR(grid.position(lo)[a] - 0.5f * grid.spacing()[a], bounds.min[a], 1e-4f);
      EXPECT_NEAR(grid.position(hi)[a] + 0.5f * grid.spacing()[a], bounds.max[a], 1e-4f);
    }
  }
  ProbeGrid g = ProbeGrid::fit_spacing(bounds, 1.0f);
  EXPECT_EQ(g.counts(), glm::ivec3(24, 5, 1));
}

TEST(ProbeGrid, FlatBoundsAndSingleProbe) {
  ProbeGrid grid(Aabb{{0.0f, 2.0f, 0.0f}, {4.0f, 2.0f, 4.0f}}, {2, 1, 2});
  EXPECT_EQ(grid.spacing().y, 0.0f);
  EXPECT_EQ(grid.position(glm::ivec3(1, 0, 1)), glm::vec3(3.0f, 2.0f, 3.0f));
  EXPECT_EQ(grid.grid_coordinate({3.0f, 7.0f, 1.0f}), glm::vec3(1.0f, 0.0f, 0.0f));
  // The smallest spacing skips the flat axis: cells of 2 m along x and z.
  EXPECT_EQ(grid.smallest_spacing(), 2.0f);
  EXPECT_EQ(ProbeGrid(Aabb{{0.0f, 0.0f, 0.0f}, {4.0f, 1.0f, 3.0f}}, {2, 4, 1}).smallest_spacing(), 0.25f);
  EXPECT_EQ(ProbeGrid().smallest_spacing(), 0.0f);  // one probe at a point: nothing to measure
}

TEST(ProbeGrid, RejectsBadInput) {
  Aabb box{{0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}};
  EXPECT_THROW(ProbeGrid(box, {0, 1, 1}), std::invalid_argument);
  EXPECT_THROW(ProbeGrid(box, {1, -3, 1}), std::invalid_argument);
  EXPECT_THROW(ProbeGrid(Aabb{}, {1, 1, 1}), std::invalid_argument);
  EXPECT_THROW(ProbeGrid(box, {4096, 4096, 4096}), std::invalid_argument);
  EXPECT_THROW(ProbeGrid::fit_spacing(box, 0.0f), std::invalid_argument);
  EXPECT_THROW(ProbeGrid::fit_spacing(box, -1.0f), std::invalid_argument);
  EXPECT_THROW(ProbeGrid::fit_spacing(box, 1e-5f), std::invalid_argument);
}

// Found by fuzzing DDPV headers: counts near 2^31 overflowed the 64-bit product x y z (UBSan:
// signed overflow) before the size check; 1e7 probes per axis overflowed fit_spacing's total.
TEST(ProbeGrid, HugeCountsAreRejectedWithoutOverflow) {
  Aabb box{{0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}};
  const int big = std::numeric_limits<int>::max();
  EXPECT_THROW(ProbeGrid(box, {big, big, big}), std::invalid_argument);
  EXPECT_THROW(ProbeGrid(box, {1, big, 1}), std::invalid_argument);
  EXPECT_THROW(ProbeGrid(box, {4096, 4096, 2}), std::invalid_argument);
  EXPECT_NO_THROW(ProbeGrid(box, {4096, 4096, 1}));  // exactly the limit, 2^24
  EXPECT_THROW(ProbeGrid::fit_spacing(Aabb{{0.0f, 0.0f, 0.0f}, {1e6f, 1e6f, 1e6f}}, 0.1f),
               std::invalid_argument);
}

TEST(ProbeGrid, AutomaticPlacement) {
  ProbeGrid g = ProbeGrid::fit_auto(Aabb{{-15.0f, 0.0f, -7.0f}, {15.0f, 12.0f, 7.0f}});
  EXPECT_EQ(g.counts(), glm::ivec3(16, 7, 8));
  ProbeGrid cube = ProbeGrid::fit_auto(Aabb{{0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}});
  EXPECT_EQ(cube.counts(), glm::ivec3(16, 16, 16));
  ProbeGrid point = ProbeGrid::fit_auto(Aabb{{1.0f, 1.0f, 1.0f}, {1.0f, 1.0f, 1.0f}});
  EXPECT_EQ(point.counts(), glm::ivec3(1));
}

// The automatic grid around an object's own bounds (ProbeGrid::fit_auto_around): a unit cube
// grows by 1/14 m on every side, so the 16 probes along each axis sit at (i - 0.5) / 14: the
// first and the last half a cell (1/28 m) outside the cube, the 14 between them inside. Without
// the margin (fit_auto) all 16^3 probes lie inside the cube.
TEST(ProbeGrid, AutomaticPlacementAroundAnObjectHasProbesOutsideIt) {
  const Aabb cube{{0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}};
  const ProbeGrid g = ProbeGrid::fit_auto_around(cube);
  EXPECT_EQ(g.counts(), glm::ivec3(16, 16, 16));
  EXPECT_NEAR(g.spacing().x, 1.0f / 14.0f, 1e-6f);
  EXPECT_NEAR(g.position(glm::ivec3(0)).x, -0.5f / 14.0f, 1e-6f);
  EXPECT_NEAR(g.position(glm::ivec3(15)).y, 14.5f / 14.0f, 1e-6f);
  std::uint32_t inside = 0, inside_without_margin = 0;
  const ProbeGrid plain = ProbeGrid::fit_auto(cube);
  for (std::uint32_t i = 0; i < g.probe_count(); ++i) {
    inside += cube.contains(g.position(i));
    inside_without_margin += cube.contains(plain.position(i));
  }
  EXPECT_EQ(inside, 14u * 14u * 14u);
  EXPECT_EQ(g.probe_count() - inside, 1352u);
  EXPECT_EQ(inside_without_margin, 4096u);

  // A flat object (a floor quad): one cell of margin gives a layer of probes above and below it.
  const ProbeGrid flat = ProbeGrid::fit_auto_around(Aabb{{-7.0f, 0.0f, -7.0f}, {7.0f, 0.0f, 7.0f}});
  EXPECT_EQ(flat.counts(), glm::ivec3(16, 2, 16));
  EXPECT_NEAR(flat.position(glm::ivec3(0, 0, 0)).y, -0.5f, 1e-5f);
  EXPECT_NEAR(flat.position(glm::ivec3(0, 1, 0)).y, 0.5f, 1e-5f);
  // A point keeps its single probe.
  EXPECT_EQ(ProbeGrid::fit_auto_around(Aabb{{1.0f, 1.0f, 1.0f}, {1.0f, 1.0f, 1.0f}}).counts(),
            glm::ivec3(1));
}
