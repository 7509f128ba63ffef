// KHR_draco_mesh_compression decoded (scene/gltf_draco.h): scenes/draco_box_draco.gltf, written
// from scenes/draco_box.gltf by Draco's encoder (scripts/make_draco_box.sh, 20-bit quantization),
// loads as the same mesh: the same triangles with the same positions, normals and UVs at their
// corners. Draco reorders vertices and faces, so triangles are compared as a set, each rotated
// to start at its smallest corner (the winding is kept).
#include <algorithm>
#include <array>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "scene/gltf_loader.h"

using namespace ddish;

namespace {

struct Corner {
  glm::vec3 p, n;
  glm::vec2 uv;
};
using Triangle = std::array<Corner, 3>;

// A sort key on a 1e-4 grid: far coarser than the quantization error, far finer than the box.
std::array<long, 8> key(const Corner& c) {
  auto q = [](float v) { return std::lround(v * 1e4f); };
  return {q(c.p.x), q(c.p.y), q(c.p.z), q(c.n.x), q(c.n.y), q(c.n.z), q(c.uv.x), q(c.uv.y)};
}

std::vector<Triangle> triangles(const scene::Scene& s) {
  std::vector<Triangle> out;
  for (const scene::Mesh& m : s.meshes)
    for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
      Triangle tri;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t i = m.indices[t + static_cast<std::size_t>(k)];
        tri[static_cast<std::size_t>(k)] = {m.positions[i], m.normals[i], m.uvs[i]};
      }
      const auto first = std::min_element(tri.begin(), tri.end(), [](const Corner& a, const Corner& b) {
        return key(a) < key(b);
      });
      std::rotate(tri.begin(), first, tri.end());
      out.push_back(tri);
    }
  std::sort(out.begin(), out.end(), [](const Triangle& a, const Triangle& b) {
    return std::make_tuple(key(a[0]), key(a[1]), key(a[2])) < std::make_tuple(key(b[0]), key(b[1]), key(b[2]));
  });
  return out;
}

scene::Scene bundled(const std::string& name) {
  return scene::load_scene(std::string(DDISH_SOURCE_DIR) + "/scenes/" + name);
}

}  // namespace

TEST(Draco, BoxEqualsItsPlainTwin) {
  const scene::Scene plain = bundled("draco_box.gltf");
  const scene::Scene draco = bundled("draco_box_draco.gltf");
  ASSERT_EQ(plain.meshes.size(), 1u);
  ASSERT_EQ(draco.meshes.size(), 1u);
  EXPECT_EQ(draco.meshes[0].positions.size(), plain.meshes[0].positions.size());
  const std::vector<Triangle> a = triangles(plain);
  const std::vector<Triangle> b = triangles(draco);
  ASSERT_EQ(a.size(), 12u);
  ASSERT_EQ(b.size(), a.size());
  float worst = 0.0f;
  for (std::size_t t = 0; t < a.size(); ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      worst = std::max({worst, glm::length(a[t][k].p - b[t][k].p), glm::length(a[t][k].n - b[t][k].n),
                        glm::length(a[t][k].uv - b[t][k].uv)});
    }
  EXPECT_LT(worst, 1e-5f) << "the largest corner difference";
  EXPECT_EQ(draco.material_of(draco.meshes[0]).base_color, plain.material_of(plain.meshes[0]).base_color);
  EXPECT_TRUE(draco.warnings.empty()) << draco.warnings.front();
}

// A stream that keeps libdraco busy for seconds (found by the GLB fuzz campaign: a count of
// texture-coordinate orientations read from the mutated stream, up to 2^31) is decoded in a
// child process and stopped at the deadline (2 s + 10 s per MiB, so 2.0 s here): one LoadError
// that says so, where before the load took 9.6 s and fuzzing stopped on it.
TEST(Draco, AStreamThatDecodesForTooLongIsOneError) {
  const std::string path = std::string(DDISH_SOURCE_DIR) + "/tests/fuzz/corpus/glb/glb_draco_orientation_count.glb";
  try {
    scene::load_scene(path);
    FAIL() << "the file loaded";
  } catch (const scene::LoadError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("2.0 s were not enough to decode"), std::string::npos) << what;
    EXPECT_NE(what.find("(a corrupt or hostile stream)"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << "one line";
  }
}
