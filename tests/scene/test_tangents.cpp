// Generated normals and tangents.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/tangents.h"

using namespace ddish;

TEST(Tangents, OrthogonalToTheNormalAndFollowU) {
  // A bent strip: two triangles in different planes sharing an edge, with a skewed UV layout.
  scene::Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {1, 1, -1}};
  m.uvs = {{0, 0}, {1, 0.2f}, {1, 1}, {0, 1}, {1.5f, 1.7f}};
  m.indices = {0, 1, 2, 0, 2, 3, 1, 4, 2};
  scene::generate_normals(m);
  scene::generate_tangents(m);
  ASSERT_EQ(m.tangents.size(), m.positions.size());
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    glm::vec3 t(m.tangents[v]);
    EXPECT_NEAR(glm::length(t), 1.0f, 1e-5f) << v;
    EXPECT_NEAR(glm::dot(t, m.normals[v]), 0.0f, 1e-5f) << v;
    EXPECT_NEAR(std::abs(m.tangents[v].w), 1.0f, 0.0f) << v;
  }
  // Vertex 3 lies on the flat triangle 0-2-3 only, where u grows along +x.
  EXPECT_NEAR(m.tangents[3].x, 1.0f, 1e-5f);
  EXPECT_EQ(m.tangents[3].w, 1.0f);  // v grows along +y = cross(N=+z, T=+x)
}

TEST(Tangents, AreaWeightedNormals) {
  // Vertex 0 is shared by a large triangle facing +z and a small one facing +x.
  scene::Mesh m;
  m.positions = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 0, -1}, {0, 1, 0}};
  m.indices = {0, 1, 2, 0, 3, 4};
  scene::generate_normals(m);
  // Face normals (unnormalised, twice the area) are (0,0,16) and (1,0,0): their sum normalised.
  glm::vec3 expected = glm::normalize(glm::vec3(1, 0, 16));
  EXPECT_NEAR(m.normals[0].x, expected.x, 1e-6f);
  EXPECT_NEAR(m.normals[0].z, expected.z, 1e-6f);
  EXPECT_NEAR(m.normals[1].z, 1.0f, 1e-6f);
}

TEST(Tangents, DegenerateUvsStillGiveAValidFrame) {
  scene::Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}};
  m.uvs = {{0.5f, 0.5f}, {0.5f, 0.5f}, {0.5f, 0.5f}};
  m.indices = {0, 2, 1};
  scene::generate_normals(m);
  scene::generate_tangents(m);
  EXPECT_NEAR(m.normals[0].y, 1.0f, 1e-6f);
  EXPECT_NEAR(glm::dot(glm::vec3(m.tangents[0]), m.normals[0]), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(glm::vec3(m.tangents[0])), 1.0f, 1e-6f);
}
