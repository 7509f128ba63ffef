// Scenes built in code for the rasterizer's tests: a UV sphere and a ground quad with one
// material each, posed and ready to render, plus the probe volumes they are lit by.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include <glm/glm.hpp>

#include "probes/probe_grid.h"
#include "probes/probe_volume.h"
#include "scene/scene.h"
#include "sh/sh_rgb.h"

namespace ddish::raster::test {

// Sorts the pixels of a shadow test: a pixel whose light ray clears the occluder by a wide margin
// must match the expected direct light to 3 %; one deep in the occluder's shadow must receive
// less than 5 % of it. Pixels near the penumbra are left out (PCF blurs them by design).
struct ShadowTally {
  int lit = 0, lit_bad = 0, shadowed = 0, shadow_bad = 0;
  double worst = 0.0;  // worst relative error over the lit pixels

  void add(const glm::vec3& got, const glm::vec3& expected, float clearance, float radius) {
    const float e = glm::length(expected);
    if (clearance > radius * 1.35f) {
      ++lit;
      const double err = glm::length(got - expected) / (e + 1e-3);
      worst = std::max(worst, err);
      if (err > 0.03) ++lit_bad;
    } else if (clearance < radius * 0.7f && e > 0.05f) {
      ++shadowed;
      if (glm::length(got) > 0.05f * e) ++shadow_bad;
    }
  }
};

inline constexpr float kTestPi = 3.14159265358979f;

// A mesh with positions, normals, UVs and tangents filled in (tangents along +x of the UVs).
inline scene::Mesh uv_sphere(float radius, int segments, int rings) {
  scene::Mesh m;
  m.name = "sphere";
  for (int r = 0; r <= rings; ++r) {
    const float theta = kTestPi * float(r) / float(rings);
    for (int s = 0; s <= segments; ++s) {
      const float phi = 2.0f * kTestPi * float(s) / float(segments);
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
      m.positions.push_back(n * radius);
      m.normals.push_back(n);
      m.uvs.push_back({float(s) / float(segments), float(r) / float(rings)});
      m.tangents.push_back({-std::sin(phi), 0.0f, -std::cos(phi), 1.0f});
    }
  }
  const auto row = static_cast<std::uint32_t>(segments + 1);
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const std::uint32_t a = std::uint32_t(r) * row + std::uint32_t(s), b = a + row;
      // Counter-clockwise seen from outside (glTF front faces).
      m.indices.insert(m.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
  for (const glm::vec3& p : m.positions) m.bounds.expand(p);
  return m;
}

// A square of side 2 * half in the y = 0 plane facing +y.
inline scene::Mesh ground_quad(float half) {
  scene::Mesh m;
  m.name = "ground";
  m.positions = {{-half, 0, -half}, {-half, 0, half}, {half, 0, half}, {half, 0, -half}};
  m.normals.assign(4, {0, 1, 0});
  m.uvs = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
  m.tangents.assign(4, {1, 0, 0, 1});
  m.indices = {0, 1, 2, 0, 2, 3};
  for (const glm::vec3& p : m.positions) m.bounds.expand(p);
  return m;
}

// A scene of one mesh instance (at the origin) with one material.
inline scene::Scene one_mesh_scene(scene::Mesh mesh, const scene::Material& material) {
  scene::Scene s;
  s.path = "test:" + mesh.name;
  mesh.material = 0;
  s.materials.push_back(material);
  s.meshes.push_back(std::move(mesh));
  scene::Node node;
  node.name = "mesh";
  node.meshes = {0};
  s.nodes.push_back(node);
  s.roots = {0};
  s.instances.push_back({0, 0, glm::mat4(1.0f)});
  s.pose(0.0);
  return s;
}

inline scene::Material make_material(const glm::vec3& base, float metallic, float roughness) {
  scene::Material m;
  m.name = "test";
  m.base_color = glm::vec4(base, 1.0f);
  m.metallic = metallic;
  m.roughness = roughness;
  return m;
}

}  // namespace ddish::raster::test

#include <glm/gtc/quaternion.hpp>

namespace ddish::raster::test {

// Adds a mesh instance at `translation` (the mesh is appended with the given material).
inline void add_instance(scene::Scene& s, scene::Mesh mesh, const scene::Material& material,
                         const glm::vec3& translation) {
  mesh.material = static_cast<int>(s.materials.size());
  s.materials.push_back(material);
  s.meshes.push_back(std::move(mesh));
  scene::Node node;
  node.name = "instance";
  node.translation = translation;
  node.meshes = {static_cast<int>(s.meshes.size()) - 1};
  s.nodes.push_back(node);
  s.roots.push_back(static_cast<int>(s.nodes.size()) - 1);
  s.instances.push_back({static_cast<int>(s.meshes.size()) - 1, static_cast<int>(s.nodes.size()) - 1,
                         glm::mat4(1.0f)});
  s.pose(s.time);
}

// A grey 2 m ground quad (roughness `ground_roughness`) under a red sphere of radius 0.3 m
// floating at 0.8 m: the light-and-shadow scene of several tests, which add their own lights.
inline scene::Scene sphere_over_ground(float ground_roughness) {
  scene::Scene s =
      one_mesh_scene(ground_quad(2.0f), make_material({0.6f, 0.6f, 0.6f}, 0.0f, ground_roughness));
  add_instance(s, uv_sphere(0.3f, 24, 12), make_material({0.8f, 0.2f, 0.2f}, 0.0f, 0.9f), {0, 0.8f, 0});
  return s;
}

// Adds a light on its own node at `position` travelling along `direction`.
inline void add_light(scene::Scene& s, scene::Light light, const glm::vec3& position,
                      const glm::vec3& direction) {
  scene::Node node;
  node.name = light.name;
  node.translation = position;
  const glm::vec3 d = glm::normalize(direction);
  const glm::vec3 up = std::abs(d.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  node.rotation = glm::quatLookAtRH(d, up);  // the node's -Z along d
  node.light = static_cast<int>(s.lights.size());
  s.nodes.push_back(node);
  s.roots.push_back(static_cast<int>(s.nodes.size()) - 1);
  light.node = static_cast<int>(s.nodes.size()) - 1;
  s.lights.push_back(light);
  s.pose(s.time);
}

// A double-sided alpha-masked material of `base` with alpha `alpha` and cutoff 0.5.
inline scene::Material masked_material(const glm::vec3& base, float alpha) {
  scene::Material m = make_material(base, 0.0f, 0.6f);
  m.base_color.a = alpha;
  m.alpha_mode = scene::AlphaMode::Mask;
  m.alpha_cutoff = 0.5f;
  m.double_sided = true;
  return m;
}

// A ground under a sphere (overdraw), two masked quads above it (one below its cutoff: cut
// out, one above: kept), a blended quad and a spot light; lit_volume adds probes with a
// constant and a linear SH term.
inline scene::Scene overdraw_scene() {
  scene::Scene s = sphere_over_ground(0.4f);
  add_instance(s, ground_quad(0.4f), masked_material({0.2f, 0.6f, 0.2f}, 0.3f), {0.0f, 1.4f, 0.0f});
  add_instance(s, ground_quad(0.4f), masked_material({0.2f, 0.2f, 0.7f}, 0.9f), {0.5f, 1.2f, 0.5f});
  scene::Material glass = make_material({0.9f, 0.8f, 0.3f}, 0.0f, 0.2f);
  glass.base_color.a = 0.5f;
  glass.alpha_mode = scene::AlphaMode::Blend;
  add_instance(s, ground_quad(0.3f), glass, {-0.5f, 1.0f, 0.4f});
  scene::Light spot;
  spot.name = "spot";
  spot.type = scene::LightType::Spot;
  spot.intensity = 10.0f;
  add_light(s, spot, {0.3f, 2.5f, 0.2f}, {0.0f, -1.0f, 0.0f});
  s.sidecar.environment = {0.0625f, 0.125f, 0.25f};
  return s;
}

inline probes::ProbeVolume lit_volume(const scene::Scene& s) {
  probes::ProbeVolume volume(probes::ProbeGrid(s.bounds(), {3, 3, 3}), 2);
  sh::ShRgb sh(2);
  sh[0] = glm::vec3(0.8f, 1.0f, 1.2f);
  sh[1] = glm::vec3(0.3f, 0.2f, 0.1f);
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i) volume.set_sh(i, sh);
  return volume;
}

}  // namespace ddish::raster::test
