// Relocation at classification (UpdateOptions::relocate): a probe inside a box moves out through
// the nearest face and is kept; one deep inside a box larger than its reach stays inactive; one
// too near a surface moves away; none leaves its cell.
#include <gtest/gtest.h>

#include <cmath>

#include "probes/probe_tracer.h"
#include "synthetic_sources.h"

using namespace ddish::probes;
using ddish::probes::synthetic::FunctionSource;
using ddish::scene::Aabb;
using ddish::trace::PathSample;
using ddish::trace::Ray;
using ddish::trace::Sampler;

namespace {

// The first hit of a ray against a closed box whose faces point outwards: from inside, the
// back of the face it leaves through; from outside, the front of the face it enters.
PathSample box_hit(const Aabb& box, const Ray& r) {
  PathSample s;
  float t0 = 0.0f, t1 = HUGE_VALF;
  for (int a = 0; a < 3; ++a) {
    const float inv = 1.0f / r.direction[a];
    float ta = (box.min[a] - r.origin[a]) * inv, tb = (box.max[a] - r.origin[a]) * inv;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (t0 > t1) return s;
  const bool inside = glm::all(glm::greaterThan(r.origin, box.min)) && glm::all(glm::lessThan(r.origin, box.max));
  s.hit = true;
  s.backface = inside;
  s.hit_distance = inside ? t1 : t0;
  return s;
}

// Probe 13 of a 3 x 3 x 3 grid over [0, 3]^3 sits at (1.5, 1.5, 1.5), in a cell of 1 m.
ProbeVolume relocated(const Aabb& box) {
  ProbeVolume v(ProbeGrid(Aabb{glm::vec3(0.0f), glm::vec3(3.0f)}, {3, 3, 3}), 2);
  FunctionSource source([box](const Ray& r, Sampler&) { return box_hit(box, r); });
  UpdateOptions o;
  o.samples = 256;
  o.relocate = true;
  ProbeTracer(source, o).update(v);
  return v;
}

bool in_cell(const ProbeVolume& v, std::uint32_t i) {
  return glm::all(glm::lessThanEqual(glm::abs(v.offset(i)), kMaxRelocation * v.grid().spacing() + 1e-6f));
}

}  // namespace

TEST(Relocation, AProbeInsideABoxMovesOutThroughTheNearestFaceAndStaysInItsCell) {
  // The box's -x face is 0.15 m from the probe; every other face farther.
  const Aabb box{{1.35f, 1.0f, 1.0f}, {2.0f, 2.0f, 2.0f}};
  const ProbeVolume v = relocated(box);
  ASSERT_EQ(v.grid().position(13u), glm::vec3(1.5f));
  EXPECT_TRUE(v.state(13).active()) << "moved out, it sees the box from outside";
  const glm::vec3 p = v.position(13);
  EXPECT_LT(p.x, box.min.x) << "outside the box";
  // Through the face along the nearest ray (d = 0.15 / cos), plus a tenth of a cell: the x
  // offset is -(0.15 + 0.1 cos), within [-0.25, -0.15].
  EXPECT_GE(v.offset(13).x, -0.25f - 1e-5f);
  EXPECT_TRUE(in_cell(v, 13));
  for (std::uint32_t i = 0; i < v.probe_count(); ++i) {
    EXPECT_TRUE(in_cell(v, i)) << i;
    if (i != 13) {
      EXPECT_EQ(v.offset(i), glm::vec3(0.0f)) << "probe " << i << " had nothing near";
    }
  }
}

TEST(Relocation, AProbeDeepInsideABoxStaysInItsCellAndBecomesInactive) {
  // Every face 0.7 m away: the move (0.8 m) is clamped at 0.45 of the cell, still inside.
  const ProbeVolume v = relocated(Aabb{glm::vec3(0.8f), glm::vec3(2.2f)});
  EXPECT_FALSE(v.state(13).active());
  EXPECT_TRUE(v.state(13).inside_geometry());
  EXPECT_TRUE(in_cell(v, 13));
  EXPECT_NEAR(glm::length(v.offset(13)), 0.45f, 0.45f * 0.75f) << "it tried, within the bound";
  EXPECT_GT(glm::length(v.offset(13)), 0.1f);
}

TEST(Relocation, AProbeTooNearASurfaceMovesAwayAndWithoutTheOptionNothingMoves) {
  // A front face 0.05 m in +x of the probe: it moves to about a tenth of a cell (0.1 m) away.
  const Aabb box{{1.55f, 1.0f, 1.0f}, {2.0f, 2.0f, 2.0f}};
  const ProbeVolume v = relocated(box);
  EXPECT_TRUE(v.state(13).active());
  EXPECT_LT(v.offset(13).x, -0.03f);
  EXPECT_GT(v.offset(13).x, -0.06f);
  EXPECT_TRUE(in_cell(v, 13));

  ProbeVolume still(ProbeGrid(Aabb{glm::vec3(0.0f), glm::vec3(3.0f)}, {3, 3, 3}), 2);
  FunctionSource source([box](const Ray& r, Sampler&) { return box_hit(box, r); });
  UpdateOptions o;
  o.samples = 256;
  ProbeTracer(source, o).update(still);
  for (std::uint32_t i = 0; i < still.probe_count(); ++i) EXPECT_EQ(still.offset(i), glm::vec3(0.0f));
}
