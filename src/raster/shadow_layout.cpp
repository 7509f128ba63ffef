#include "raster/shadow_layout.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/scene.h"
#include "scene/view.h"

namespace ddish::raster {

namespace {

std::array<glm::vec3, 8> corners(const scene::Aabb& b) {
  std::array<glm::vec3, 8> c;
  for (int i = 0; i < 8; ++i)
    c[static_cast<std::size_t>(i)] = {(i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y,
                                      (i & 4) ? b.max.z : b.min.z};
  return c;
}

// An up vector that is not parallel to dir.
glm::vec3 any_up(const glm::vec3& dir) {
  return std::abs(dir.y) < 0.99f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
}

float farthest_corner(const glm::vec3& p, const scene::Aabb& bounds) {
  float d = 0.0f;
  for (const glm::vec3& c : corners(bounds)) d = std::max(d, glm::length(c - p));
  return d;
}

// Near plane of a perspective light: a small fraction of the scene, so that casters close to
// the light are kept while depth precision (D32 float) stays ample.
float light_near(const scene::Aabb& bounds) {
  return std::max(1e-3f, 1e-3f * glm::length(bounds.extent()));
}

// View-space depth of the scene's far side seen from the view: cascades end there, not at a
// zfar of 1000 that would waste every texel.
float view_depth_extent(const scene::View& v, const scene::Aabb& bounds) {
  float far_z = 0.0f;
  for (const glm::vec3& c : corners(bounds)) far_z = std::max(far_z, -(v.view * glm::vec4(c, 1.0f)).z);
  return far_z;
}

void add_directional(const scene::Light& light, const scene::View& view, const scene::Aabb& bounds,
                     const ShadowSettings& s, ShadowLayout& out) {
  const glm::vec3 dir = glm::normalize(light.direction);
  // Near and far of the view's projection (Vulkan depth 0..1): z_ndc = A + B / z_view.
  const glm::mat4& p = view.projection;
  const float znear = p[3][2] / p[2][2];
  const float zfar_proj = p[3][2] / (p[2][2] + 1.0f);
  const float zfar = std::clamp(view_depth_extent(view, bounds), znear * 1.01f, zfar_proj);
  const std::vector<float> splits = cascade_splits(znear, zfar, s.cascades, s.split_lambda);
  const glm::mat4 inv_proj = glm::inverse(p);
  const glm::mat4 inv_view = glm::inverse(view.view);
  // Light-space depth range over the whole scene: casters outside a cascade's slice still cast.
  const glm::mat4 light_view = glm::lookAtRH(glm::vec3(0.0f), dir, any_up(dir));
  float zmin = 1e30f, zmax = -1e30f;
  for (const glm::vec3& c : corners(bounds)) {
    const float z = (light_view * glm::vec4(c, 1.0f)).z;
    zmin = std::min(zmin, z);
    zmax = std::max(zmax, z);
  }
  // Padding keeps the depth range non-empty for flat scenes lit head-on.
  const float pad = 0.01f * glm::length(bounds.extent()) + 1e-3f;
  zmin -= pad;
  zmax += pad;
  float begin = znear;
  for (float end : splits) {
    // The slice's 8 corners in world space, and the sphere around them: a sphere's projection
    // does not change size as the camera turns, so the texel size of a cascade is stable.
    std::array<glm::vec3, 8> pts;
    int k = 0;
    for (float depth : {begin, end}) {
      for (int i = 0; i < 4; ++i) {
        const glm::vec4 ndc((i & 1) ? 1.0f : -1.0f, (i & 2) ? 1.0f : -1.0f, 0.0f, 1.0f);
        glm::vec4 cam = inv_proj * ndc;
        cam /= cam.w;
        const glm::vec3 ray = glm::vec3(cam) / -cam.z;  // the camera ray at unit depth
        pts[static_cast<std::size_t>(k++)] = glm::vec3(inv_view * glm::vec4(ray * depth, 1.0f));
      }
    }
    glm::vec3 center(0.0f);
    for (const glm::vec3& q : pts) center += q * 0.125f;
    float radius = 0.0f;
    for (const glm::vec3& q : pts) radius = std::max(radius, glm::length(q - center));
    // Snap the centre to whole texels in light space so the map does not shimmer as it moves.
    const float texel = 2.0f * radius / float(s.map_size);
    glm::vec3 lc = glm::vec3(light_view * glm::vec4(center, 1.0f));
    lc.x = std::floor(lc.x / texel) * texel;
    lc.y = std::floor(lc.y / texel) * texel;
    const glm::mat4 proj = glm::orthoRH_ZO(lc.x - radius, lc.x + radius, lc.y - radius,
                                           lc.y + radius, -zmax, -zmin);
    ShadowLayerData layer;
    layer.light_view_proj = proj * light_view;
    layer.params = {0.0f, 1.5f * texel, 0.0f, 0.0f};
    out.layers.push_back(layer);
    begin = end;
  }
}

void add_perspective(const glm::vec3& pos, const glm::vec3& dir, const glm::vec3& up, float fov,
                     const scene::Aabb& bounds, const ShadowSettings& s, ShadowLayout& out) {
  const float znear = light_near(bounds);
  const float zfar = std::max(farthest_corner(pos, bounds), znear * 2.0f);
  ShadowLayerData layer;
  layer.light_view_proj =
      glm::perspectiveRH_ZO(fov, 1.0f, znear, zfar) * glm::lookAtRH(pos, pos + dir, up);
  // Texel size grows with distance: the shader multiplies this by the distance to the light.
  layer.params = {0.0f, 1.5f * 2.0f * std::tan(0.5f * fov) / float(s.map_size), 1.0f, 0.0f};
  out.layers.push_back(layer);
}

}  // namespace

std::vector<float> cascade_splits(float znear, float zfar, int count, float lambda) {
  if (count < 1 || count > 4) throw std::invalid_argument("shadow cascades must be 1..4");
  if (!(znear > 0.0f) || !(zfar > znear)) throw std::invalid_argument("cascade range must be 0 < near < far");
  std::vector<float> splits;
  for (int i = 1; i <= count; ++i) {
    const float f = float(i) / float(count);
    const float log_split = znear * std::pow(zfar / znear, f);
    const float uniform = znear + (zfar - znear) * f;
    splits.push_back(lambda * log_split + (1.0f - lambda) * uniform);
  }
  splits.back() = zfar;
  return splits;
}

ShadowLayout layout_shadows(std::span<const scene::Light> lights, std::span<const scene::View> views,
                            const scene::Aabb& bounds, const ShadowSettings& s) {
  ShadowLayout out;
  const bool can_shadow = !bounds.empty() && !views.empty();
  for (const scene::Light& light : lights) {
    LightData d;
    const glm::vec3 dir = glm::length(light.direction) > 0.0f ? glm::normalize(light.direction)
                                                                : glm::vec3(0.0f, 0.0f, -1.0f);
    d.position_range = glm::vec4(light.position, light.range);
    d.radiant = glm::vec4(light.radiant(), 0.0f);
    LightKind kind = LightKind::point;
    if (light.type == scene::LightType::Directional) kind = LightKind::directional;
    if (light.type == scene::LightType::Spot) {
      kind = LightKind::spot;
      // trace/lights.cpp's smooth cone: saturate(cos * scale + offset)^2.
      const float cos_outer = std::cos(light.outer_cone);
      const float cos_inner = std::cos(light.inner_cone);
      const float scale = 1.0f / std::max(1e-3f, cos_inner - cos_outer);
      d.spot_shadow.x = scale;
      d.spot_shadow.y = -cos_outer * scale;
    }
    d.direction_type = glm::vec4(dir, float(static_cast<std::uint32_t>(kind)));
    const auto first = static_cast<float>(out.layers.size());
    if (can_shadow && s.enabled && kind == LightKind::directional) {
      add_directional(light, views.front(), bounds, s, out);
    } else if (can_shadow && s.enabled && kind == LightKind::spot) {
      // The cone plus a margin for the PCF kernel, kept below 180 degrees.
      const float fov = std::min(2.0f * light.outer_cone * 1.05f + 0.02f, glm::radians(170.0f));
      add_perspective(light.position, dir, any_up(dir), fov, bounds, s, out);
    } else if (can_shadow && kind == LightKind::point && s.point_shadows) {
      const std::array<glm::vec3, 6> axes{{{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}};
      for (const glm::vec3& axis : axes)
        add_perspective(light.position, axis, any_up(axis), glm::radians(90.0f), bounds, s, out);
    }
    const auto count = static_cast<float>(out.layers.size()) - first;
    if (count > 0.0f) {
      d.spot_shadow.z = first;
      d.spot_shadow.w = count;
    }
    out.lights.push_back(d);
  }
  return out;
}

}  // namespace ddish::raster
