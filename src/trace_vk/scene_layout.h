// The scene as the GPU probe tracer reads it, laid out on the host (std430, the structs of
// shaders/include/trace_scene.glsl): object-space vertices and each mesh's triangles in a
// spatially sorted order (Morton order of their centroids: lavapipe's BVH keeps the input order,
// and an unsorted mesh traces orders of magnitude slower, DESIGN.md), one material per mesh,
// instances, the emissive triangles in world space with their power CDF (trace::LightSet's
// choice, by area x luminance), the punctual lights, the BSDF's albedo table, and the
// environment map with trace::EnvironmentLight's sampling tables. Deformed meshes' vertices are
// rewritten when their pose changes. Building it needs no device, so it is tested on its own
// (tests/trace_vk/scene_layout_test.cpp).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace ddish::scene {
struct Scene;
struct Mesh;
}  // namespace ddish::scene

namespace ddish::trace_vk {

struct GpuVertex {
  glm::vec4 position_u{0.0f};  // object-space position, UV0.x
  glm::vec4 normal_v{0.0f};    // object-space normal (zero: none), UV0.y
  glm::vec4 tangent{0.0f};     // glTF tangent, w handedness (zero: none)
  glm::vec4 color{1.0f};       // COLOR_0 (white: none)
  glm::vec4 uv1{0.0f};         // TEXCOORD_1 in xy
};

struct GpuMesh {
  std::uint32_t first_index = 0;
  std::uint32_t first_vertex = 0;
  std::uint32_t triangle_count = 0;
  std::uint32_t material = 0;
};

struct GpuInstance {
  glm::mat4 object_to_world{1.0f};
  glm::mat4 normal_matrix{1.0f};
  std::uint32_t mesh = 0;
  std::int32_t emissive_first = -1;
  std::uint32_t mirrored = 0;
  std::uint32_t pad = 0;
};

inline constexpr std::uint32_t kMaterialDoubleSided = 1u;
inline constexpr std::uint32_t kMaterialUnlit = 2u;
inline constexpr std::uint32_t kMaterialMask = 4u;
inline constexpr std::uint32_t kMaterialBlend = 8u;

// A material's texture slot: the texture (-1: none), its UV set, addressing and filters
// (packed: wrap s | wrap t << 2 | mag << 4 | min << 5 | mip << 6, the scene enums' values), and
// KHR_texture_transform as the rows of its 2 x 3 matrix with the area scale.
struct GpuTextureSlot {
  std::int32_t texture = -1;
  std::uint32_t texcoord = 0;
  std::uint32_t sampler = 0;
  float area_scale = 1.0f;
  glm::vec4 row0{1.0f, 0.0f, 0.0f, 0.0f};
  glm::vec4 row1{0.0f, 1.0f, 0.0f, 0.0f};
};

struct GpuMaterial {
  glm::vec4 base_color{1.0f};
  glm::vec4 emission_metallic{0.0f};
  glm::vec4 dielectric_f0_roughness{0.04f, 0.04f, 0.04f, 1.0f};
  float specular = 1.0f;
  std::uint32_t flags = 0;
  float alpha_cutoff = 0.5f;
  float normal_scale = 1.0f;
  GpuTextureSlot base_color_texture, metallic_roughness_texture, normal_texture, emissive_texture;
};

// A texture's mip chain in the texel buffer: its first level in the level list and its count.
struct GpuTexture {
  std::uint32_t first_level = 0;
  std::uint32_t levels = 0;
  float half_log2_texels = 0.0f;  // log2 of sqrt(texels at level 0), trace::MipTexture's
  std::uint32_t pad = 0;
};

struct GpuTextureLevel {
  std::uint32_t offset = 0;  // first texel in the texel buffer
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t pad = 0;
};

struct GpuEmissive {
  glm::vec4 p0_area{0.0f};
  glm::vec4 e1_magnitude{0.0f};
  glm::vec4 e2_double_sided{0.0f};
  glm::vec4 normal_cdf{0.0f};
  glm::vec4 radiance_prob{0.0f};
  std::uint32_t instance = 0;  // for the emissive texture: the instance and its primitive
  std::uint32_t prim = 0;
  std::uint32_t pad0 = 0, pad1 = 0;
};

struct GpuLight {
  glm::vec4 position_type{0.0f};
  glm::vec4 direction_range{0.0f};
  glm::vec4 radiant{0.0f};
  glm::vec4 spot{0.0f};
};

// The environment map's size and rotation (trace_environment.glsl's EnvironmentParams; width 0:
// no map, or a black one).
struct GpuEnvironment {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  float cos_rotation = 1.0f;
  float sin_rotation = 0.0f;
};

// The albedo table's size: trace::DielectricSpecularAlbedo's 32 x 32 nodes.
inline constexpr int kAlbedoNodes = 32;

// The triangles of `mesh` (indices, 3 per triangle) in Morton order of their centroids.
std::vector<std::uint32_t> spatially_sorted_indices(const scene::Mesh& mesh);

struct SceneLayout {
  std::vector<GpuVertex> vertices;
  std::vector<std::uint32_t> indices;  // per mesh, sorted, relative to its first vertex
  std::vector<GpuMesh> meshes;
  // Per mesh: whether Scene::pose deforms it (skin, morph targets), and the pose_version its
  // vertices above are of.
  std::vector<bool> deformed;
  std::vector<std::uint64_t> pose_versions;
  std::vector<GpuMaterial> materials;  // one per mesh
  std::vector<GpuInstance> instances;
  std::vector<GpuEmissive> emissive;   // the emissive instances' triangles, in index order
  std::vector<GpuLight> lights;
  // E (32 x 32, row = roughness node), dE/dF0 (32 x 32), E_avg (32), dE_avg/dF0 (32).
  std::vector<float> albedo;
  // trace::TextureSet's mip chains, texel for texel (RGBA8 packed, R in the low byte).
  std::vector<GpuTexture> textures;
  std::vector<GpuTextureLevel> texture_levels;
  std::vector<std::uint32_t> texels;
  // The environment map as trace::EnvironmentLight samples it (its own tables, in floats): the
  // texels' radiance with, in w, each texel's density in (u, v) (weight x width x height /
  // total); the row CDF (height + 1) followed by every row's column CDF (width + 1 each).
  GpuEnvironment environment;
  std::vector<glm::vec4> environment_texels;
  std::vector<float> environment_cdf;

  // The whole layout of a posed scene.
  static SceneLayout build(const scene::Scene& scene);
  // Rewrites the vertices of the deformed meshes whose pose changed since (their pose_version),
  // and returns those meshes (their triangles and order stay: only positions, normals and
  // tangents move). Then place() follows the rest.
  std::vector<std::uint32_t> repose(const scene::Scene& scene);
  // Re-places instances, emissive triangles and lights after scene.pose.
  void place(const scene::Scene& scene);
};

}  // namespace ddish::trace_vk
