// The scene model: everything ddish renders, loaded from glTF 2.0 (see gltf_loader.h) and posed
// at a time t (see Scene::pose). Plain data; the tracer and the rasterizer build their own
// acceleration structures and GPU resources from it.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "scene/aabb.h"
#include "scene/animation.h"
#include "scene/deformation.h"
#include "scene/environment_map.h"

namespace ddish::scene {

// A decoded texture: RGBA8, row 0 at the top (as glTF images are stored). Each glTF image is
// decoded once and shared by every material and texture slot that uses it.
struct Texture {
  std::string name;
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba8;  // width * height * 4 bytes
};

// How texture coordinates outside [0, 1] wrap (the glTF sampler's wrapS / wrapT).
enum class Wrap { Repeat, ClampToEdge, MirroredRepeat };

// The glTF sampler's filters. Magnification is nearest or linear; minification adds how mip
// levels are chosen (None: level 0 only, glTF's plain NEAREST / LINEAR minFilter). A sampler
// without filters gets linear filtering with linear mips (glTF leaves the choice to viewers).
enum class Filter { Nearest, Linear };
enum class MipFilter { None, Nearest, Linear };

// KHR_texture_transform as the affine map it defines on texture coordinates:
// uv' = offset + R(rotation) * (scale * uv), with R = [[cos, sin], [-sin, cos]]: the UVs turn
// counter-clockwise as seen in glTF's UV space, where v points down, as the extension's text
// says. Its GLSL listing, read as column-major, gives the transpose (counter-clockwise with v
// up); Khronos's TextureTransformTest model, Blender, Babylon.js and three.js follow the text
// (glTF issue #1563), and with the listing's matrix that model's arrow points at its red
// "opposite direction" marker. Identity when absent.
struct TextureTransform {
  glm::vec2 offset{0.0f};
  float rotation = 0.0f;  // radians
  glm::vec2 scale{1.0f};
  // Rows of the 2 x 3 matrix: u' = dot(row0, (u, v, 1)), v' = dot(row1, (u, v, 1)).
  glm::vec3 row0() const { return {std::cos(rotation) * scale.x, std::sin(rotation) * scale.y, offset.x}; }
  glm::vec3 row1() const { return {-std::sin(rotation) * scale.x, std::cos(rotation) * scale.y, offset.y}; }
  glm::vec2 apply(glm::vec2 uv) const {
    const glm::vec3 h(uv, 1.0f);
    return {glm::dot(row0(), h), glm::dot(row1(), h)};
  }
  // |det| of the linear part: how much the map scales UV areas.
  float area_scale() const { return std::abs(scale.x * scale.y); }
  bool identity() const {
    return offset == glm::vec2(0.0f) && rotation == 0.0f && scale == glm::vec2(1.0f);
  }
};

struct TextureSlot {
  int texture = -1;   // index into Scene::textures, -1 when the slot is empty
  int texcoord = 0;   // which UV set: 0 (TEXCOORD_0) or 1 (TEXCOORD_1), after the transform's override
  Wrap wrap_s = Wrap::Repeat;
  Wrap wrap_t = Wrap::Repeat;
  Filter mag_filter = Filter::Linear;
  Filter min_filter = Filter::Linear;
  MipFilter mip_filter = MipFilter::Linear;
  TextureTransform transform;  // KHR_texture_transform
  explicit operator bool() const { return texture >= 0; }
};

enum class AlphaMode { Opaque, Mask, Blend };

// glTF metallic-roughness material with all its factors and textures.
struct Material {
  std::string name;
  glm::vec4 base_color{1.0f};
  float metallic = 1.0f;
  float roughness = 1.0f;
  glm::vec3 emissive{0.0f};        // emissiveFactor
  float emissive_strength = 1.0f;  // KHR_materials_emissive_strength
  float normal_scale = 1.0f;
  float occlusion_strength = 1.0f;
  AlphaMode alpha_mode = AlphaMode::Opaque;
  float alpha_cutoff = 0.5f;
  bool double_sided = false;
  // KHR_materials_unlit: the surface shows its base colour (factor × texture) as radiance,
  // whatever the light, and reflects nothing; both renderers treat it so.
  bool unlit = false;
  // The dielectric layer (KHR_materials_ior, KHR_materials_specular; factors only, their
  // textures are not read): F0 = ((ior - 1) / (ior + 1))^2 * specular_color (clamped to 1) and
  // the layer's weight `specular`. The defaults are glTF's dielectric, F0 = 0.04, weight 1.
  float ior = 1.5f;
  float specular = 1.0f;
  glm::vec3 specular_color{1.0f};

  TextureSlot base_color_texture;          // sRGB
  TextureSlot metallic_roughness_texture;  // linear: G = roughness, B = metallic
  TextureSlot normal_texture;              // linear, tangent space
  TextureSlot occlusion_texture;           // linear, R
  TextureSlot emissive_texture;            // sRGB

  // Normal-incidence reflectance of the dielectric layer before the specular weight.
  glm::vec3 dielectric_f0() const {
    const float r = (ior - 1.0f) / (ior + 1.0f);
    return glm::min(glm::vec3(r * r) * specular_color, glm::vec3(1.0f));
  }
  // Emitted radiance before the emissive texture: emissiveFactor × emissive_strength.
  glm::vec3 emission() const { return emissive * emissive_strength; }
  bool is_emissive() const { return glm::any(glm::greaterThan(emission(), glm::vec3(0.0f))); }
};

// One glTF primitive, triangulated and indexed. Vertex arrays all have positions.size() entries.
struct Mesh {
  std::string name;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;   // generated (area-weighted) when the file has none
  std::vector<glm::vec2> uvs;       // UV0; zeros when the file has none
  std::vector<glm::vec2> uvs1;      // TEXCOORD_1; zeros when the file has none
  // COLOR_0 (linear RGBA; vec3 colours get alpha 1), multiplying the base colour factor and
  // texture in both renderers; white when the file has none.
  std::vector<glm::vec4> colors;
  std::vector<glm::vec4> tangents;  // xyz tangent, w handedness; generated when missing
  std::vector<std::uint32_t> indices;  // 3 per triangle
  int material = -1;                   // index into Scene::materials; -1 = glTF default material
  Aabb bounds;                         // object space (of the current pose)
  // Morph targets and skin influences with the rest pose; empty for a rigid mesh. A deformed
  // mesh's arrays above are its current pose, written by Scene::pose.
  Deformation deformation;
  // Counts the times pose() rewrote the arrays, so the tracer and the rasterizer re-upload a
  // deformed mesh only when its pose changed.
  std::uint64_t pose_version = 0;

  std::size_t triangle_count() const { return indices.size() / 3; }
  // The UV set a texture slot reads (0 or 1).
  const std::vector<glm::vec2>& uv_set(int texcoord) const { return texcoord == 1 ? uvs1 : uvs; }
};

// A node of the glTF hierarchy. Local TRS is what animations drive; world is derived by pose().
struct Node {
  std::string name;
  int parent = -1;
  std::vector<int> children;
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  glm::vec3 scale{1.0f};
  glm::mat4 world{1.0f};
  std::vector<int> meshes;  // Scene::meshes drawn at this node (one per glTF primitive)
  int camera = -1;          // index into Scene::cameras
  int light = -1;           // index into Scene::lights
  int skin = -1;            // index into Scene::skins: skins this node's meshes
  // Morph-target weights of this node's mesh: the node's "weights", else the mesh's, else 0;
  // "weights" animation channels drive them.
  std::vector<float> weights;
};

// A mesh that pose() deforms (morph targets, or skin influences drawn by a node with a skin).
// Each is drawn by one node only: the loader gives every further node drawing it its own copy,
// as the pose depends on the node's weights and skin.
struct DeformedMesh {
  int mesh = -1;
  int node = -1;
  int skin = -1;  // -1: morph targets only
  // The weights and joint matrices of the last pose, to skip posing when they did not change.
  std::vector<float> weights;
  std::vector<glm::mat4> joints;
  bool posed = false;
};

// A mesh placed in the world. Instances of the same mesh share its vertex data (a deformed
// mesh is shared only by the EXT_mesh_gpu_instancing instances of its one node).
struct Instance {
  int mesh = -1;
  int node = -1;
  glm::mat4 transform{1.0f};  // object to world, updated by pose(): the node's world * local
  glm::mat4 local{1.0f};      // under the node: an EXT_mesh_gpu_instancing instance's TRS
};

enum class LightType { Directional, Point, Spot };

// KHR_lights_punctual in radiometric units (DESIGN.md "Light units"): a directional light's
// intensity is the irradiance on a surface facing it, a point or spot light's intensity is
// radiant intensity (power per steradian). The loader converts the file's photometric units
// (Sidecar::light_units) with kLumensPerWatt.
struct Light {
  std::string name;
  LightType type = LightType::Point;
  glm::vec3 color{1.0f};
  float intensity = 1.0f;
  float range = 0.0f;  // 0 = infinite
  float inner_cone = 0.0f;
  float outer_cone = 0.785398163f;  // pi/4, the glTF default
  int node = -1;
  // World-space placement, updated by pose(). direction is where the light travels (-Z of its node).
  glm::vec3 position{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};

  glm::vec3 radiant() const { return color * intensity; }
};

// A perspective camera. World placement (eye, forward, up) is updated by pose().
struct Camera {
  std::string name;
  float yfov = 0.8f;  // radians
  std::optional<float> aspect;
  float znear = 0.01f;
  float zfar = 1000.0f;
  int node = -1;  // -1: not in the hierarchy (the framing camera), pose() leaves it where it is
  glm::vec3 eye{0.0f};
  glm::vec3 forward{0.0f, 0.0f, -1.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
};

// The units of KHR_lights_punctual intensities in the file. glTF specifies photometric units
// (candela for point and spot lights, lux for directional ones); a sidecar may declare
// radiometric ones (W/sr, W/m^2), as ddish's own and the benchmark scenes do.
enum class LightUnits { Photometric, Radiometric };

// Luminous efficacy that converts glTF's photometric light units to radiometric ones: 683 lm/W
// (the SI definition of the candela, at 540 THz), as KHR_lights_punctual suggests.
inline constexpr float kLumensPerWatt = 683.0f;

// The sidecar's environment.map: an equirectangular .exr or .hdr that lights the scene, as
// --environment FILE with --environment-rotation and --environment-intensity would.
struct SidecarEnvironmentMap {
  std::string file;           // resolved against the sidecar's folder; exists when parsed
  float rotation_deg = 0.0f;  // environment.rotation, about +Y
  float intensity = 1.0f;     // environment.intensity
};

// What the sidecar NAME.ddish.json adds to a glTF file (format: ../shared/scenes/README.md).
struct Sidecar {
  glm::vec3 environment{0.0f};               // uniform radiance of escaping rays
  bool environment_given = false;            // environment.radiance is in the sidecar
  std::optional<SidecarEnvironmentMap> environment_map;  // environment.map
  LightUnits light_units = LightUnits::Photometric;
  std::optional<glm::ivec3> probe_counts;    // probe grid counts
  std::optional<Aabb> probe_bounds;          // probe grid bounds; default: the scene's bounds
  std::string camera;                        // default camera node name; empty = first camera
};

struct Scene {
  std::string path;  // the file it was loaded from
  std::vector<Texture> textures;
  std::vector<Material> materials;
  std::vector<Mesh> meshes;
  std::vector<Node> nodes;
  std::vector<int> roots;  // nodes of the glTF default scene without a parent
  std::vector<Instance> instances;
  std::vector<Light> lights;
  std::vector<Camera> cameras;
  std::vector<Animation> animations;
  std::vector<Skin> skins;
  std::vector<DeformedMesh> deformed;
  Sidecar sidecar;
  // An equirectangular environment (--environment) in place of the uniform one; the uniform
  // radiance is then 0 (app/lighting_options.h). Every renderer adds both.
  std::shared_ptr<const EnvironmentMap> environment_map;
  double time = 0.0;  // the time the scene is posed at
  // What the loader skipped but could still load (points/lines, orthographic cameras, ...),
  // one line each, for `ddish info`.
  std::vector<std::string> warnings;

  // Poses the scene at time t (seconds): evaluates every animation, then recomputes node world
  // transforms, instance transforms, light and camera placements, and the vertices of deformed
  // meshes (skins, morph targets). Returns the indices of the instances whose transform or
  // vertices changed, so consumers rebuild only what moved (a changed mesh has a new
  // pose_version).
  std::vector<int> pose(double t);

  // Duration of the longest animation (0 when there is none).
  double animation_duration() const;

  // World-space bounds of every instance at the current pose.
  Aabb bounds() const;

  std::size_t triangle_count() const;  // over instances (after instancing)

  // The material of a mesh, or the glTF default material when the mesh has none.
  const Material& material_of(const Mesh& mesh) const;

  // The default camera: the sidecar's named camera, else the first camera, else none.
  const Camera* default_camera() const;
  const Camera* find_camera(const std::string& name) const;

  glm::vec3 environment() const { return sidecar.environment; }
};

}  // namespace ddish::scene
