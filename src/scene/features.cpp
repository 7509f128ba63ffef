#include "scene/features.h"

#include <set>

namespace ddish::scene {

namespace {

bool is_glossy(const Material& m) {
  return m.roughness < kGlossyRoughness || bool(m.metallic_roughness_texture);
}

}  // namespace

SceneFeatures analyze(const Scene& scene) {
  SceneFeatures f;
  f.triangles = scene.triangle_count();
  f.instances = scene.instances.size();
  f.meshes = scene.meshes.size();
  std::set<const Material*> used;
  for (const auto& inst : scene.instances)
    used.insert(&scene.material_of(scene.meshes[std::size_t(inst.mesh)]));
  std::set<int> textures;
  for (const Material* m : used) {
    f.glossy_materials += is_glossy(*m);
    f.metal_materials += m->metallic >= kMetalThreshold;
    f.normal_mapped_materials += bool(m->normal_texture);
    f.masked_materials += m->alpha_mode == AlphaMode::Mask;
    f.blended_materials += m->alpha_mode == AlphaMode::Blend;
    f.double_sided_materials += m->double_sided;
    f.emissive_materials += m->is_emissive();
    f.dielectric_materials += m->ior != 1.5f || m->specular != 1.0f || m->specular_color != glm::vec3(1.0f);
    bool textured = false, second_uv = false, transformed = false;
    for (const TextureSlot* s : {&m->base_color_texture, &m->metallic_roughness_texture,
                                 &m->normal_texture, &m->occlusion_texture, &m->emissive_texture})
      if (*s) {
        textures.insert(s->texture);
        textured = true;
        second_uv |= s->texcoord == 1;
        transformed |= !s->transform.identity();
      }
    f.textured_materials += textured;
    f.second_uv_materials += second_uv;
    f.texture_transform_materials += transformed;
  }
  std::set<int> colored;
  for (const auto& inst : scene.instances)
    if (!scene.meshes[std::size_t(inst.mesh)].colors.empty()) colored.insert(inst.mesh);
  f.vertex_colored_meshes = colored.size();
  for (const DeformedMesh& d : scene.deformed) {
    f.skinned_meshes += d.skin >= 0;
    f.morphed_meshes += !scene.meshes[std::size_t(d.mesh)].deformation.targets.empty();
  }
  f.materials_used = used.size();
  f.textures_used = textures.size();
  for (const auto& l : scene.lights) {
    f.directional_lights += l.type == LightType::Directional;
    f.point_lights += l.type == LightType::Point;
    f.spot_lights += l.type == LightType::Spot;
  }
  f.cameras = scene.cameras.size();
  f.animations = scene.animations.size();
  f.animation_duration = scene.animation_duration();
  f.environment = scene.environment();
  f.environment_map = scene.environment_map != nullptr;
  f.bounds = scene.bounds();
  return f;
}

RenderPlan make_plan(const SceneFeatures& f) {
  RenderPlan p;
  auto leave_out = [&p](bool& flag, const char* what, const char* why) {
    flag = false;
    p.left_out.push_back({what, why});
  };
  if (f.punctual_lights() == 0) {
    leave_out(
        p.direct_lights, "direct punctual lighting",
        "the scene has no punctual lights (emission and sky reach the views through the probes)");
    leave_out(p.shadow_maps, "shadow maps", "the scene has no punctual lights");
  } else if (f.directional_lights + f.spot_lights == 0) {
    leave_out(p.shadow_maps, "directional and spot shadow maps",
              "the scene has no directional or spot lights");
  }
  if (f.point_lights == 0)
    leave_out(p.point_shadows, "cube shadow maps", "the scene has no point lights");
  if (f.glossy_materials == 0 && f.metal_materials == 0)
    leave_out(
        p.specular_probes, "specular probe term",
        "no glossy materials (roughness >= 0.5, no metallic-roughness texture) and no metals "
        "(metallic < 0.5)");
  if (f.textures_used == 0)
    leave_out(p.texture_sampling, "texture sampling", "no material uses a texture");
  if (f.normal_mapped_materials == 0)
    leave_out(p.normal_mapping, "normal mapping", "no material has a normal map");
  if (f.masked_materials == 0) leave_out(p.alpha_test, "alpha test", "no masked materials");
  if (f.blended_materials == 0)
    leave_out(p.alpha_blend, "transparent pass", "no blended materials");
  if (f.emissive_materials == 0) leave_out(p.emission, "emissive term", "no emissive surfaces");
  if (!f.has_environment())
    leave_out(p.environment, "environment lookup",
              "environment radiance is 0 (escaping rays are black)");
  if (f.animations == 0)
    leave_out(p.animation, "per-frame scene updates",
              "the scene has no animations, so geometry, acceleration structures and shadow maps "
              "are built once");
  return p;
}

}  // namespace ddish::scene
