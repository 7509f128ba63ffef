// Stiff and extreme input (docs/extreme-cases.md): zero-area and degenerate triangles are
// accepted and get finite normals and tangents; non-finite radiometric numbers (light
// intensity, emissive strength, sidecar environment radiance) and numbers that overflow float
// when narrowed are rejected with one clear line. NaN/Inf positions: test_bad_input.cpp
// (BadInput.NonFinitePositions).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "gltf_builder.h"
#include "scene/gltf_loader.h"
#include "scene/sidecar.h"
#include "scene/tangents.h"

using namespace ddish;
using ddish::test::BufferMode;
using ddish::test::GltfBuilder;
using ddish::test::TempDir;

namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Writes b, then replaces the JSON number `marker` (as dump() wrote it) by `replacement`: JSON
// writers cannot produce 1e400, so the out-of-range literal is put into the text directly.
std::string write_with(const GltfBuilder& b, const TempDir& dir, const std::string& marker,
                       const std::string& replacement) {
  const std::string path = b.write(dir.path.string(), "x.gltf", BufferMode::External);
  std::string text = read_text(path);
  const std::size_t at = text.find(marker);
  EXPECT_NE(at, std::string::npos) << marker;
  if (at != std::string::npos) text.replace(at, marker.size(), replacement);
  test::write_file(path, text);
  return path;
}

GltfBuilder quad_with_light(double intensity) {
  GltfBuilder b;
  b.add_node({{"mesh", b.add_quad_mesh()}});
  b.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  b.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"name", "lamp"}, {"type", "point"}, {"intensity", intensity}}};
  b.add_node({{"name", "lamp"},
              {"translation", {0.0, 1.0, 0.0}},
              {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  return b;
}

}  // namespace

// Three triangles: an ordinary one, a zero-area one with three distinct collinear vertices, and
// one with a repeated vertex. The loader keeps all three (nothing to reject: they are valid
// glTF), and the generated normals and tangents are unit length and finite everywhere,
// including at the vertex that only degenerate triangles touch.
TEST(ExtremeScene, ZeroAreaTrianglesLoadWithFiniteNormalsAndTangents) {
  TempDir dir("extreme_degenerate");
  GltfBuilder b;
  std::vector<float> pos = {0, 0, 0, 1, 0, 0, 0, 1, 0,      // ordinary, facing +z
                            2, 0, 0, 3, 0, 0, 4, 0, 0,      // collinear: zero area
                            5, 5, 5};                       // only on a repeated-vertex triangle
  std::vector<float> uv = {0, 0, 1, 0, 0, 1, 0, 0, 0.5f, 0, 1, 0, 0.3f, 0.3f};
  nlohmann::json prim;
  prim["attributes"]["POSITION"] = b.add_floats(pos, "VEC3", 7);
  prim["attributes"]["TEXCOORD_0"] = b.add_floats(uv, "VEC2", 7);
  prim["indices"] = b.add_indices({0, 1, 2, 3, 4, 5, 6, 6, 1});
  b.doc["meshes"] = {{{"primitives", {prim}}}};
  b.add_node({{"mesh", 0}});
  const scene::Scene s = scene::load_scene(b.write(dir.path.string(), "d.gltf", BufferMode::External));
  ASSERT_EQ(s.meshes.size(), 1u);
  const scene::Mesh& m = s.meshes[0];
  EXPECT_EQ(m.triangle_count(), 3u);
  ASSERT_EQ(m.normals.size(), 7u);
  ASSERT_EQ(m.tangents.size(), 7u);
  for (std::size_t i = 0; i < 7; ++i) {
    ASSERT_TRUE(finite(m.normals[i])) << i;
    ASSERT_TRUE(finite(glm::vec3(m.tangents[i]))) << i;
    EXPECT_NEAR(glm::length(m.normals[i]), 1.0f, 1e-5f) << i;
    EXPECT_NEAR(glm::length(glm::vec3(m.tangents[i])), 1.0f, 1e-5f) << i;
    EXPECT_NEAR(glm::dot(glm::vec3(m.tangents[i]), m.normals[i]), 0.0f, 1e-5f) << i;
    EXPECT_EQ(std::abs(m.tangents[i].w), 1.0f) << i;
  }
  // The ordinary triangle's normal is untouched by its zero-area neighbours (area weighting
  // gives them zero weight): +z at vertex 0.
  EXPECT_NEAR(m.normals[0].z, 1.0f, 1e-6f);
}

// The generators alone on a mesh of nothing but degenerate triangles (all vertices equal):
// the documented fallbacks, +Y normals and any unit tangent orthogonal to them.
TEST(ExtremeScene, AllDegenerateMeshFallsBackToAValidFrame) {
  scene::Mesh m;
  m.positions.assign(3, glm::vec3(1e-20f));
  m.uvs.assign(3, glm::vec2(0.0f));
  m.indices = {0, 1, 2, 2, 1, 0};
  scene::generate_normals(m);
  scene::generate_tangents(m);
  for (std::size_t i = 0; i < 3; ++i) {
    ASSERT_TRUE(finite(m.normals[i]));
    EXPECT_NEAR(glm::length(m.normals[i]), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::length(glm::vec3(m.tangents[i])), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::dot(glm::vec3(m.tangents[i]), m.normals[i]), 0.0f, 1e-5f);
  }
}

// A light intensity of 1e39 (finite as a double, Inf once narrowed to float) used to load as
// an Inf light; it is rejected now, naming the light. 1e400 never gets that far: the JSON
// parser itself refuses it ("number overflow"), still as one LoadError naming the file.
TEST(ExtremeScene, NonFiniteLightIntensityIsRejected) {
  for (const char* bad : {"1e400", "-1e400"}) {
    TempDir dir("extreme_light_json");
    const std::string path = write_with(quad_with_light(12345.5), dir, "12345.5", bad);
    const std::string msg = test::load_message(path);
    EXPECT_EQ(msg.rfind(path, 0), 0u) << msg;
    EXPECT_NE(msg.find("number overflow"), std::string::npos) << bad << ": " << msg;
  }
  for (const char* bad : {"1e39", "-1e39"}) {
    TempDir dir("extreme_light");
    const std::string path = write_with(quad_with_light(12345.5), dir, "12345.5", bad);
    const std::string msg = test::load_message(path);
    EXPECT_NE(msg.find("lamp"), std::string::npos) << bad << ": " << msg;
    EXPECT_NE(msg.find("not finite"), std::string::npos) << bad << ": " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
  // The largest float is still a (very bright) light: 3e38 cd, converted to W/sr (no sidecar,
  // so glTF's photometric units).
  TempDir dir("extreme_light_ok");
  const std::string path = write_with(quad_with_light(12345.5), dir, "12345.5", "3.0e38");
  const scene::Scene s = scene::load_scene(path);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_FLOAT_EQ(s.lights[0].intensity, 3.0e38f / scene::kLumensPerWatt);
}

TEST(ExtremeScene, NonFiniteEmissiveStrengthIsRejected) {
  TempDir dir("extreme_emissive");
  GltfBuilder b;
  b.doc["extensionsUsed"] = {"KHR_materials_emissive_strength"};
  b.doc["materials"] = {{{"name", "glow"},
                         {"emissiveFactor", {1.0, 1.0, 1.0}},
                         {"extensions",
                          {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4321.5}}}}}}};
  b.add_node({{"mesh", b.add_quad_mesh(true, 0)}});
  const std::string msg = test::load_message(write_with(b, dir, "4321.5", "1e39"));
  EXPECT_NE(msg.find("glow"), std::string::npos) << msg;
  EXPECT_NE(msg.find("emissiveStrength is not finite"), std::string::npos) << msg;
  // A colour factor that overflows float is rejected too (it used to pass as a finite double).
  TempDir dir2("extreme_emissive_factor");
  GltfBuilder c;
  c.doc["materials"] = {{{"name", "hot"}, {"emissiveFactor", {1.0, 765.25, 1.0}}}};
  c.add_node({{"mesh", c.add_quad_mesh(true, 0)}});
  const std::string msg2 = test::load_message(write_with(c, dir2, "765.25", "1e39"));
  EXPECT_NE(msg2.find("emissiveFactor is not finite"), std::string::npos) << msg2;
}

TEST(ExtremeScene, NodeTranslationBeyondFloatIsRejected) {
  TempDir dir("extreme_node");
  GltfBuilder b;
  b.add_node({{"name", "far"}, {"mesh", b.add_quad_mesh()}, {"translation", {0.0, 0.0, 98765.5}}});
  const std::string msg = test::load_message(write_with(b, dir, "98765.5", "1e39"));
  EXPECT_NE(msg.find("far"), std::string::npos) << msg;
  EXPECT_NE(msg.find("not finite"), std::string::npos) << msg;
}

// Sidecar environment radiance: JSON has no NaN literal and the parser refuses 1e400 (both
// "not valid JSON"); 1e39 parses as a finite double but overflows float, which used to give an
// infinite sky and is rejected now; negative radiance is rejected.
TEST(ExtremeScene, SidecarEnvironmentMustBeFiniteAndNonNegative) {
  auto message = [](const std::string& radiance) {
    try {
      scene::parse_sidecar(R"({"environment": {"radiance": )" + radiance + "}}", "s.ddish.json");
    } catch (const scene::LoadError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  EXPECT_NE(message("[1, NaN, 1]").find("not valid JSON"), std::string::npos);
  EXPECT_NE(message("[1, 1e400, 1]").find("not valid JSON"), std::string::npos);
  EXPECT_NE(message("[1, 1e39, 1]").find("finite numbers"), std::string::npos)
      << message("[1, 1e39, 1]");
  EXPECT_NE(message("[1, -1e-9, 1]").find("must not be negative"), std::string::npos);
  for (const char* bad : {"[1, NaN, 1]", "[1, 1e400, 1]", "[1, 1e39, 1]", "[1, -1e-9, 1]"})
    EXPECT_EQ(message(bad).rfind("s.ddish.json", 0), 0u) << message(bad);
  const scene::Sidecar ok = scene::parse_sidecar(R"({"environment": {"radiance": [0, 3e38, 1e-30]}})",
                                                 "s.ddish.json");
  EXPECT_EQ(ok.environment.x, 0.0f);
  EXPECT_FLOAT_EQ(ok.environment.y, 3e38f);
}
