// glTF materials, KHR_lights_punctual lights and cameras to the scene model.
#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

#include "scene/gltf_internal.h"

namespace ddish::scene::gltf {

namespace {

// An optional factor: its value as a float, or the fallback where it is not finite (the check is
// on the narrowed float, which a finite double beyond float's range would turn into Inf).
float finite_or(double v, float fallback) {
  const float f = float(v);
  return std::isfinite(f) ? f : fallback;
}

// A radiometric quantity (light intensity, emissive strength): a non-finite value is an error,
// never replaced by a default, since it would otherwise put Inf or NaN into every renderer.
float finite_number(const Context& ctx, double v, const std::string& what) {
  const float f = float(v);
  if (!std::isfinite(f)) ctx.fail(what + " is not finite");
  return f;
}

template <int N>
glm::vec<N, float> vector_or(const Context& ctx, const std::vector<double>& v,
                             glm::vec<N, float> fallback, const std::string& what) {
  if (v.empty()) return fallback;
  if (v.size() != std::size_t(N))
    ctx.fail(what + " has " + std::to_string(v.size()) + " values, expected " + std::to_string(N));
  glm::vec<N, float> out;
  for (int i = 0; i < N; ++i) {
    out[i] = float(v[std::size_t(i)]);  // a finite double beyond float's range becomes Inf
    if (!std::isfinite(out[i])) ctx.fail(what + " is not finite");
  }
  return out;
}

Wrap wrap_of(int gl) {
  switch (gl) {
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE:
      return Wrap::ClampToEdge;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT:
      return Wrap::MirroredRepeat;
    default:
      return Wrap::Repeat;
  }
}

Filter mag_filter_of(int gl) {
  return gl == TINYGLTF_TEXTURE_FILTER_NEAREST ? Filter::Nearest : Filter::Linear;
}

// glTF minFilter -> (filter within a level, how levels are chosen); -1 (absent): trilinear.
std::pair<Filter, MipFilter> min_filter_of(int gl) {
  switch (gl) {
    case TINYGLTF_TEXTURE_FILTER_NEAREST:
      return {Filter::Nearest, MipFilter::None};
    case TINYGLTF_TEXTURE_FILTER_LINEAR:
      return {Filter::Linear, MipFilter::None};
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST:
      return {Filter::Nearest, MipFilter::Nearest};
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST:
      return {Filter::Linear, MipFilter::Nearest};
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR:
      return {Filter::Nearest, MipFilter::Linear};
    default:
      return {Filter::Linear, MipFilter::Linear};
  }
}

// A finite number member of a KHR_texture_transform object, or the fallback when absent.
float transform_number(const Context& ctx, const tinygltf::Value& v, const char* key, float fallback,
                       const std::string& what) {
  if (!v.Has(key)) return fallback;
  const tinygltf::Value& x = v.Get(key);
  if (!x.IsNumber()) ctx.fail(what + ": KHR_texture_transform " + key + " is not a number");
  return finite_number(ctx, x.GetNumberAsDouble(), what + ": KHR_texture_transform " + key);
}

glm::vec2 transform_pair(const Context& ctx, const tinygltf::Value& v, const char* key,
                         glm::vec2 fallback, const std::string& what) {
  if (!v.Has(key)) return fallback;
  const tinygltf::Value& x = v.Get(key);
  if (!x.IsArray() || x.ArrayLen() != 2 || !x.Get(0).IsNumber() || !x.Get(1).IsNumber())
    ctx.fail(what + ": KHR_texture_transform " + key + " must be an array of two numbers");
  const std::string label = what + ": KHR_texture_transform " + key;
  return {finite_number(ctx, x.Get(0).GetNumberAsDouble(), label),
          finite_number(ctx, x.Get(1).GetNumberAsDouble(), label)};
}

// Maps a glTF texture reference to the decoded image it samples (Scene::textures are images),
// with its sampler's wrap and filter modes and its KHR_texture_transform.
TextureSlot slot(const Context& ctx, int texture, int texcoord, const tinygltf::ExtensionMap& ext,
                 const std::string& what) {
  TextureSlot s;
  if (texture < 0) return s;
  const auto& m = ctx.model;
  if (std::size_t(texture) >= m.textures.size())
    ctx.fail(what + ": texture " + std::to_string(texture) + " does not exist");
  int source = m.textures[std::size_t(texture)].source;
  if (source < 0 || std::size_t(source) >= m.images.size())
    ctx.fail(what + ": texture " + std::to_string(texture) + " has no valid image source");
  auto it = ext.find("KHR_texture_transform");
  if (it != ext.end() && it->second.IsObject()) {
    const tinygltf::Value& v = it->second;
    s.transform.offset = transform_pair(ctx, v, "offset", glm::vec2(0.0f), what);
    s.transform.rotation = transform_number(ctx, v, "rotation", 0.0f, what);
    s.transform.scale = transform_pair(ctx, v, "scale", glm::vec2(1.0f), what);
    // The extension's texCoord overrides the texture info's.
    if (v.Has("texCoord")) {
      if (!v.Get("texCoord").IsInt())
        ctx.fail(what + ": KHR_texture_transform texCoord is not an integer");
      texcoord = v.Get("texCoord").GetNumberAsInt();
    }
  }
  if (texcoord != 0 && texcoord != 1)
    ctx.fail(what + ": uses TEXCOORD_" + std::to_string(texcoord) +
             ", only TEXCOORD_0 and TEXCOORD_1 are supported");
  s.texture = source;
  s.texcoord = texcoord;
  int sampler = m.textures[std::size_t(texture)].sampler;
  if (sampler >= 0) {
    if (std::size_t(sampler) >= m.samplers.size())
      ctx.fail(what + ": sampler " + std::to_string(sampler) + " does not exist");
    const auto& gs = m.samplers[std::size_t(sampler)];
    s.wrap_s = wrap_of(gs.wrapS);
    s.wrap_t = wrap_of(gs.wrapT);
    s.mag_filter = mag_filter_of(gs.magFilter);
    std::tie(s.min_filter, s.mip_filter) = min_filter_of(gs.minFilter);
  }
  return s;
}

// KHR_materials_ior and KHR_materials_specular (factors; their textures are not read).
void load_dielectric(const Context& ctx, const tinygltf::Material& gm, Material& mat,
                     const std::string& what, Scene& scene) {
  const double ior = extension_number(gm.extensions, "KHR_materials_ior", "ior", 1.5);
  mat.ior = finite_number(ctx, ior, what + " KHR_materials_ior ior");
  if (mat.ior < 1.0f) {
    scene.warnings.push_back(what + ": KHR_materials_ior ior " + std::to_string(mat.ior) +
                             " is below 1; 1.5 is used");
    mat.ior = 1.5f;
  }
  auto it = gm.extensions.find("KHR_materials_specular");
  if (it == gm.extensions.end() || !it->second.IsObject()) return;
  const tinygltf::Value& v = it->second;
  const std::string label = what + " KHR_materials_specular";
  if (v.Has("specularFactor")) {
    if (!v.Get("specularFactor").IsNumber()) ctx.fail(label + " specularFactor is not a number");
    mat.specular = std::clamp(
        finite_number(ctx, v.Get("specularFactor").GetNumberAsDouble(), label + " specularFactor"),
        0.0f, 1.0f);
  }
  if (v.Has("specularColorFactor")) {
    const tinygltf::Value& c = v.Get("specularColorFactor");
    if (!c.IsArray() || c.ArrayLen() != 3)
      ctx.fail(label + " specularColorFactor must be an array of three numbers");
    for (int k = 0; k < 3; ++k) {
      if (!c.Get(k).IsNumber()) ctx.fail(label + " specularColorFactor must be an array of three numbers");
      mat.specular_color[k] = std::max(
          0.0f, finite_number(ctx, c.Get(k).GetNumberAsDouble(), label + " specularColorFactor"));
    }
  }
  if (v.Has("specularTexture") || v.Has("specularColorTexture"))
    scene.warnings.push_back(what + ": KHR_materials_specular textures are not read (factors only)");
}

}  // namespace

double extension_number(const tinygltf::ExtensionMap& extensions, const std::string& ext,
                        const std::string& key, double fallback) {
  auto it = extensions.find(ext);
  if (it == extensions.end() || !it->second.IsObject() || !it->second.Has(key)) return fallback;
  const tinygltf::Value& v = it->second.Get(key);
  return v.IsNumber() ? v.GetNumberAsDouble() : fallback;
}

void load_materials(const Context& ctx, Scene& scene) {
  for (std::size_t i = 0; i < ctx.model.materials.size(); ++i) {
    const auto& gm = ctx.model.materials[i];
    Material mat;
    mat.name = gm.name.empty() ? "material" + std::to_string(i) : gm.name;
    const std::string what = "material '" + mat.name + "'";
    const auto& pbr = gm.pbrMetallicRoughness;
    mat.base_color =
        vector_or<4>(ctx, pbr.baseColorFactor, glm::vec4(1.0f), what + " baseColorFactor");
    mat.metallic = glm::clamp(finite_or(pbr.metallicFactor, 1.0f), 0.0f, 1.0f);
    mat.roughness = glm::clamp(finite_or(pbr.roughnessFactor, 1.0f), 0.0f, 1.0f);
    mat.emissive = vector_or<3>(ctx, gm.emissiveFactor, glm::vec3(0.0f), what + " emissiveFactor");
    mat.emissive_strength = std::max(
        0.0f, finite_number(ctx,
                            extension_number(gm.extensions, "KHR_materials_emissive_strength",
                                             "emissiveStrength", 1.0),
                            what + " emissiveStrength"));
    mat.normal_scale = finite_or(gm.normalTexture.scale, 1.0f);
    mat.occlusion_strength = glm::clamp(finite_or(gm.occlusionTexture.strength, 1.0f), 0.0f, 1.0f);
    if (gm.alphaMode == "MASK")
      mat.alpha_mode = AlphaMode::Mask;
    else if (gm.alphaMode == "BLEND")
      mat.alpha_mode = AlphaMode::Blend;
    else if (gm.alphaMode == "OPAQUE" || gm.alphaMode.empty())
      mat.alpha_mode = AlphaMode::Opaque;
    else
      ctx.fail(what + ": unknown alphaMode '" + gm.alphaMode + "'");
    mat.alpha_cutoff = std::max(0.0f, finite_or(gm.alphaCutoff, 0.5f));
    mat.double_sided = gm.doubleSided;
    mat.unlit = gm.extensions.count("KHR_materials_unlit") > 0;
    load_dielectric(ctx, gm, mat, what, scene);
    mat.base_color_texture = slot(ctx, pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                  pbr.baseColorTexture.extensions, what + " baseColorTexture");
    mat.metallic_roughness_texture =
        slot(ctx, pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
             pbr.metallicRoughnessTexture.extensions, what + " metallicRoughnessTexture");
    mat.normal_texture = slot(ctx, gm.normalTexture.index, gm.normalTexture.texCoord,
                              gm.normalTexture.extensions, what + " normalTexture");
    mat.occlusion_texture = slot(ctx, gm.occlusionTexture.index, gm.occlusionTexture.texCoord,
                                 gm.occlusionTexture.extensions, what + " occlusionTexture");
    mat.emissive_texture = slot(ctx, gm.emissiveTexture.index, gm.emissiveTexture.texCoord,
                                gm.emissiveTexture.extensions, what + " emissiveTexture");
    scene.materials.push_back(std::move(mat));
  }
}

Light make_light(const Context& ctx, int index, int node) {
  const auto& m = ctx.model;
  if (index < 0 || std::size_t(index) >= m.lights.size())
    ctx.fail("node " + std::to_string(node) + ": KHR_lights_punctual light " +
             std::to_string(index) + " does not exist");
  const auto& gl = m.lights[std::size_t(index)];
  Light light;
  light.name = gl.name.empty() ? m.nodes[std::size_t(node)].name : gl.name;
  const std::string what = "light '" + light.name + "'";
  if (gl.type == "directional")
    light.type = LightType::Directional;
  else if (gl.type == "point")
    light.type = LightType::Point;
  else if (gl.type == "spot")
    light.type = LightType::Spot;
  else
    ctx.fail(what + ": unknown light type '" + gl.type + "'");
  light.color = vector_or<3>(ctx, gl.color, glm::vec3(1.0f), what + " color");
  // A non-finite intensity (1e400 in the file parses as infinity, and 1e39 overflows float)
  // is an error, not a silent 1.
  light.intensity = finite_number(ctx, gl.intensity, what + ": intensity");
  light.range = std::max(0.0f, finite_or(gl.range, 0.0f));
  if (light.type == LightType::Spot) {
    light.inner_cone = finite_or(gl.spot.innerConeAngle, 0.0f);
    light.outer_cone = finite_or(gl.spot.outerConeAngle, 0.785398163f);
    if (light.inner_cone < 0.0f || light.outer_cone <= light.inner_cone ||
        light.outer_cone > 1.5707964f)
      ctx.fail(what + ": spot cone angles must satisfy 0 <= inner < outer <= pi/2");
  }
  if (light.intensity < 0.0f) ctx.fail(what + ": negative intensity");
  light.node = node;
  return light;
}

bool make_camera(const Context& ctx, int index, int node, Scene& scene, Camera& out) {
  const auto& m = ctx.model;
  if (index < 0 || std::size_t(index) >= m.cameras.size())
    ctx.fail("node " + std::to_string(node) + ": camera " + std::to_string(index) +
             " does not exist");
  const auto& gc = m.cameras[std::size_t(index)];
  const std::string& node_name = m.nodes[std::size_t(node)].name;
  // The sidecar names the default camera by node, so the node name wins.
  out.name = !node_name.empty() ? node_name
             : !gc.name.empty() ? gc.name
                                : "camera" + std::to_string(index);
  if (gc.type != "perspective") {
    scene.warnings.push_back("camera '" + out.name + "': only perspective cameras are supported");
    return false;
  }
  const auto& p = gc.perspective;
  if (!(p.yfov > 0.0 && p.yfov < 3.14159) || !(p.znear > 0.0))
    ctx.fail("camera '" + out.name + "': yfov must lie in (0, pi) and znear must be positive");
  out.yfov = float(p.yfov);
  if (p.aspectRatio > 0.0) out.aspect = float(p.aspectRatio);
  out.znear = float(p.znear);
  // zfar 0 means an infinite projection in glTF; ddish uses a far plane, so keep its default
  // unless that would lie in front of the near plane.
  out.zfar = p.zfar > p.znear ? float(p.zfar) : std::max(out.zfar, 1000.0f * out.znear);
  out.node = node;
  return true;
}

}  // namespace ddish::scene::gltf
