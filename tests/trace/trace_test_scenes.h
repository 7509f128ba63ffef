// Small programmatic scenes for the tracer tests (quads, boxes), plus the statistics and the
// quadrature the tests compare Monte-Carlo estimates against.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"
#include "trace/bsdf.h"
#include "trace/sampler.h"
#include "trace/tracer.h"

namespace ddish::trace::testing {

inline scene::Material diffuse(glm::vec3 color, float roughness = 1.0f, float metallic = 0.0f) {
  scene::Material m;
  m.base_color = glm::vec4(color, 1.0f);
  m.metallic = metallic;
  m.roughness = roughness;
  return m;
}

inline scene::Material emitter(glm::vec3 radiance) {
  scene::Material m = diffuse(glm::vec3(0.0f));
  m.emissive = radiance;
  return m;
}

inline int add_material(scene::Scene& s, const scene::Material& m) {
  s.materials.push_back(m);
  return static_cast<int>(s.materials.size()) - 1;
}

// A mesh with flat normals from each triangle's winding (or the given ones), tangent +x.
inline int add_mesh(scene::Scene& s, std::vector<glm::vec3> positions, std::vector<std::uint32_t> indices,
                    int material, std::vector<glm::vec2> uvs = {}, std::vector<glm::vec3> normals = {}) {
  scene::Mesh mesh;
  mesh.positions = std::move(positions);
  mesh.indices = std::move(indices);
  mesh.material = material;
  if (normals.empty()) {
    normals.assign(mesh.positions.size(), glm::vec3(0.0f));
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      const glm::vec3 n = glm::cross(mesh.positions[mesh.indices[t + 1]] - mesh.positions[mesh.indices[t]],
                                     mesh.positions[mesh.indices[t + 2]] - mesh.positions[mesh.indices[t]]);
      for (int k = 0; k < 3; ++k) normals[mesh.indices[t + static_cast<std::size_t>(k)]] += n;
    }
    for (auto& n : normals) n = glm::dot(n, n) > 0.0f ? glm::normalize(n) : n;
  }
  mesh.normals = std::move(normals);
  mesh.uvs = uvs.empty() ? std::vector<glm::vec2>(mesh.positions.size(), glm::vec2(0.0f)) : std::move(uvs);
  mesh.tangents.assign(mesh.positions.size(), glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
  for (const auto& p : mesh.positions) mesh.bounds.expand(p);
  s.meshes.push_back(std::move(mesh));
  return static_cast<int>(s.meshes.size()) - 1;
}

inline int add_instance(scene::Scene& s, int mesh, const glm::mat4& transform = glm::mat4(1.0f)) {
  scene::Instance inst;
  inst.mesh = mesh;
  inst.transform = transform;
  s.instances.push_back(inst);
  return static_cast<int>(s.instances.size()) - 1;
}

// A quad centred at c spanning c ± a ± b; its front faces cross(a, b). UV (0,0) at c - a - b,
// (1,1) at c + a + b.
inline int add_quad(scene::Scene& s, glm::vec3 c, glm::vec3 a, glm::vec3 b, int material) {
  const int mesh = add_mesh(s, {c - a - b, c + a - b, c + a + b, c - a + b}, {0, 1, 2, 0, 2, 3}, material,
                            {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}});
  return add_instance(s, mesh);
}

// An axis-aligned box [lo, hi] whose six faces face inward (open_top: the +y face is left out).
inline void add_box_inward(scene::Scene& s, glm::vec3 lo, glm::vec3 hi, int material, bool open_top = false) {
  const glm::vec3 c = 0.5f * (lo + hi);
  const glm::vec3 h = 0.5f * (hi - lo);
  const glm::vec3 x(h.x, 0, 0), y(0, h.y, 0), z(0, 0, h.z);
  add_quad(s, c - x, y, z, material);                 // faces +x
  add_quad(s, c + x, z, y, material);                 // faces -x
  add_quad(s, c - y, z, x, material);                 // faces +y
  if (!open_top) add_quad(s, c + y, x, z, material);  // faces -y
  add_quad(s, c - z, x, y, material);                 // faces +z
  add_quad(s, c + z, y, x, material);                 // faces -z
}

inline scene::Texture solid_texture(int w, int h, std::function<glm::u8vec4(int, int)> texel) {
  scene::Texture t;
  t.width = w;
  t.height = h;
  t.rgba8.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4u);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const glm::u8vec4 v = texel(x, y);
      for (int c = 0; c < 4; ++c) t.rgba8[(static_cast<std::size_t>(y) * w + x) * 4 + c] = v[c];
    }
  }
  return t;
}

// Mean and standard error of n independent estimates.
struct Estimate {
  glm::dvec3 mean{0.0};
  glm::dvec3 stderr_{0.0};
};

inline Estimate estimate(const Tracer& tracer, const Ray& ray, int n, std::uint64_t seed = 7) {
  glm::dvec3 sum(0.0), sum2(0.0);
  for (int i = 0; i < n; ++i) {
    Sampler sampler(seed, 0, static_cast<std::uint64_t>(i));
    const glm::dvec3 l(tracer.trace_path(ray, sampler).radiance);
    sum += l;
    sum2 += l * l;
  }
  Estimate e;
  e.mean = sum / double(n);
  const glm::dvec3 var = glm::max(sum2 / double(n) - e.mean * e.mean, glm::dvec3(0.0));
  e.stderr_ = glm::sqrt(var / double(n));
  return e;
}

// Prints an estimate against its expected value, in sigmas, for the test log.
inline void report(const char* what, double mean, double stderr_, double expected) {
  std::printf("[ figures  ] %s: estimate %.6g, expected %.6g, stderr %.3g, off by %.2f sigma\n", what, mean,
              expected, stderr_, stderr_ > 0.0 ? (mean - expected) / stderr_ : 0.0);
}

// ∫ f(wo, wi) cos(wi) dwi over the hemisphere by midpoint quadrature in (cos theta, phi): the
// directional albedo the tests expect light to be reflected with.
inline glm::dvec3 directional_albedo(const Bsdf& bsdf, const glm::vec3& wo, int n = 600) {
  glm::dvec3 sum(0.0);
  const double dmu = 1.0 / n;
  const double dphi = 2.0 * M_PI / (2 * n);
  for (int i = 0; i < n; ++i) {
    const double mu = (i + 0.5) * dmu;
    const double s = std::sqrt(1.0 - mu * mu);
    for (int j = 0; j < 2 * n; ++j) {
      const double phi = (j + 0.5) * dphi;
      const glm::vec3 wi(float(s * std::cos(phi)), float(s * std::sin(phi)), float(mu));
      sum += glm::dvec3(bsdf.eval(wo, wi)) * mu * dmu * dphi;
    }
  }
  return sum;
}

}  // namespace ddish::trace::testing
