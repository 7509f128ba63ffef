// Light sampling for next-event estimation. Punctual lights (KHR_lights_punctual, radiometric
// units per DESIGN.md) are deltas: sampled exactly, one shadow ray each. Emissive triangles
// (every triangle of every instance whose material emits) form one list sampled by power
// (area × luminance of the emission factor) through a CDF, uniformly by area within a triangle,
// with the density converted to solid angle so that MIS can weigh it against BSDF sampling.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace ddish::scene {
struct Scene;
struct Light;
}  // namespace ddish::scene

namespace ddish::trace {

class TextureSet;

struct LightSample {
  glm::vec3 wi{0.0f};  // unit direction from the shading point toward the light
  float distance = std::numeric_limits<float>::infinity();  // to the light point; inf: directional
  glm::vec3 radiance{0.0f};      // arriving radiance (delta lights: irradiance-like, see below)
  float pdf = 0.0f;              // solid-angle density; 0 marks a delta light (no MIS)
  glm::vec3 point{0.0f};         // the point on an area light (shadow rays end there, offset)
  glm::vec3 normal{0.0f};        // its geometric normal, facing the shading point
  float point_magnitude = 0.0f;  // coordinate magnitude of the light triangle (ray offsets)
};

// A punctual light's contribution at p: for delta lights `radiance` is what multiplies
// f·cos directly (point/spot: I·attenuation/d²; directional: the irradiance E). False when the
// light gives nothing at p (outside a spot cone, beyond range, zero intensity).
bool sample_punctual(const scene::Light& light, const glm::vec3& p, LightSample& out);

// glTF's recommended spot falloff: (saturate(cos·scale + offset))², smooth between the cones.
float spot_attenuation(const scene::Light& light, const glm::vec3& to_point_dir);

class LightSet {
 public:
  // The scene and textures must outlive this object.
  LightSet(const scene::Scene& scene, const TextureSet& textures);

  // Re-places the punctual lights and the emissive triangles of `moved` instances.
  void update(const scene::Scene& scene, std::span<const int> moved);

  std::span<const scene::Light> punctual() const;
  bool has_emissive() const { return total_power_ > 0.0; }
  std::size_t emissive_triangle_count() const { return tris_.size(); }

  // One point on the emissive triangles for shading point p; u in [0,1)^3.
  bool sample_emissive(const glm::vec3& p, const glm::vec3& u, LightSample& out) const;
  // Solid-angle density with which sample_emissive picks a point on (instance, prim) seen at
  // `distance` with |cos| = cos_light at the light; 0 for a triangle that is not in the list.
  float emissive_pdf(int instance, int prim, float distance, float cos_light) const;

 private:
  struct Triangle {
    glm::vec3 p0{0.0f}, e1{0.0f}, e2{0.0f};
    glm::vec3 n{0.0f};  // unit geometric normal (front side)
    float area = 0.0f;
    float magnitude = 0.0f;
    int instance = -1;
    int prim = -1;
    bool double_sided = false;
  };
  void place(std::size_t first, int instance);
  void build_cdf();

  const scene::Scene* scene_;
  const TextureSet* textures_;
  std::vector<scene::Light> punctual_;
  std::vector<Triangle> tris_;
  std::vector<int> instance_first_;  // per instance: index of its first triangle in tris_, or -1
  std::vector<double> cdf_;          // tris_.size() + 1 entries, cdf_[0] = 0
  double total_power_ = 0.0;
};

}  // namespace ddish::trace
