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
  // v grows along +y there; glTF's v runs down the image, so the normal map's +Y (image up)
  // is -y = -cross(N=+z, T=+x): w = -1.
  EXPECT_EQ(m.tangents[3].w, -1.0f);
}

// A quad laid out as glTF images are: u to the right (+x), v down the image, so up the image
// is world +y. MikkTSpace's bitangent (image up, the normal map's +Y) is then +y =
// cross(N, T) with w = +1: the frame a file's own tangents would give (NormalTangentMirrorTest).
// The old generator followed +v and gave w = -1, which dented NormalTangentTest.
TEST(Tangents, GltfQuadBitangentPointsUpTheImage) {
  scene::Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  m.uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  m.indices = {0, 1, 2, 0, 2, 3};
  scene::generate_normals(m);
  scene::generate_tangents(m);
  ASSERT_EQ(m.positions.size(), 4u);  // one orientation: nothing split
  for (std::size_t v = 0; v < 4; ++v) {
    EXPECT_NEAR(m.tangents[v].x, 1.0f, 1e-6f) << v;
    EXPECT_EQ(m.tangents[v].w, 1.0f) << v;
    const glm::vec3 b = glm::cross(m.normals[v], glm::vec3(m.tangents[v])) * m.tangents[v].w;
    EXPECT_NEAR(b.y, 1.0f, 1e-6f) << v;
  }
}

// Two triangles sharing the edge 1-2 whose UVs mirror across it (u runs +x on the left, -x on
// the right): MikkTSpace gives the shared vertices one tangent per orientation, so they are
// split; every attribute is copied, and each triangle keeps its own handedness.
TEST(Tangents, MirroredUvsSplitTheSharedVertices) {
  scene::Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {2, 0, 0}};
  m.uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 1}};
  m.uvs1 = {{0, 0}, {0.1f, 0}, {0.2f, 0}, {0.3f, 0}};
  m.colors = {glm::vec4(1), glm::vec4(0.5f), glm::vec4(0.25f), glm::vec4(0)};
  m.indices = {0, 1, 2, 1, 3, 2};
  scene::generate_normals(m);
  scene::generate_tangents(m);
  ASSERT_EQ(m.positions.size(), 6u);  // vertices 1 and 2 copied
  ASSERT_EQ(m.tangents.size(), 6u);
  ASSERT_EQ(m.uvs.size(), 6u);
  ASSERT_EQ(m.uvs1.size(), 6u);
  ASSERT_EQ(m.colors.size(), 6u);
  for (int k = 0; k < 3; ++k) {  // the first triangle: u along +x, right-handed
    const std::uint32_t v = m.indices[std::size_t(k)];
    EXPECT_NEAR(m.tangents[v].x, 1.0f, 1e-6f) << v;
    EXPECT_EQ(m.tangents[v].w, 1.0f) << v;
  }
  for (int k = 3; k < 6; ++k) {  // the mirrored one: u along -x, left-handed, bitangent still +y
    const std::uint32_t v = m.indices[std::size_t(k)];
    EXPECT_NEAR(m.tangents[v].x, -1.0f, 1e-6f) << v;
    EXPECT_EQ(m.tangents[v].w, -1.0f) << v;
    const glm::vec3 b = glm::cross(m.normals[v], glm::vec3(m.tangents[v])) * m.tangents[v].w;
    EXPECT_NEAR(b.y, 1.0f, 1e-6f) << v;
  }
  EXPECT_EQ(m.indices[3], 4u);  // vertex 1's copy
  EXPECT_EQ(m.indices[5], 5u);  // vertex 2's copy
  EXPECT_EQ(m.positions[4], m.positions[1]);
  EXPECT_EQ(m.uvs1[5], m.uvs1[2]);
  EXPECT_EQ(m.colors[4], m.colors[1]);
}

// The corner angle weights: a vertex shared by a wide and a narrow corner leans to the wide one.
TEST(Tangents, CornersAreWeightedByTheirAngle) {
  // Vertex 0 is shared by triangle A (corner 90 degrees, u along +x) and triangle B (corner
  // atan 0.2 = 11.3 degrees, its UVs A's turned -90 degrees: u along -y); both face +z with the
  // same orientation, so nothing is split.
  scene::Mesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, -0.2f, 0}, {-1, 0, 0}};
  m.uvs = {{0, 1}, {1, 1}, {0, 0}, {0.2f, 2}, {0, 2}};
  m.indices = {0, 1, 2, 0, 4, 3};
  scene::generate_normals(m);
  scene::generate_tangents(m);
  ASSERT_EQ(m.positions.size(), 5u);
  // A's tangent is +x, B's -y: their sum weighted by the corner angles.
  const float a = 1.5707964f, b = std::atan2(0.2f, 1.0f);
  const glm::vec3 expected = glm::normalize(glm::vec3(a, -b, 0.0f));
  EXPECT_NEAR(m.tangents[0].x, expected.x, 1e-4f);
  EXPECT_NEAR(m.tangents[0].y, expected.y, 1e-4f);
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
