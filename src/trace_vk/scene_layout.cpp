#include "trace_vk/scene_layout.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "scene/scene.h"
#include "trace/environment_light.h"
#include "trace/ggx.h"
#include "trace/specular_albedo.h"
#include "trace/surface.h"
#include "trace/texture_lookup.h"

namespace ddish::trace_vk {

namespace {

float luminance(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

// Spreads the low 10 bits of v to every third bit (for a 30-bit Morton code).
std::uint32_t spread_bits(std::uint32_t v) {
  v &= 0x3FFu;
  v = (v | (v << 16)) & 0x030000FFu;
  v = (v | (v << 8)) & 0x0300F00Fu;
  v = (v | (v << 4)) & 0x030C30C3u;
  v = (v | (v << 2)) & 0x09249249u;
  return v;
}

GpuTextureSlot slot_of(const scene::TextureSlot& slot, std::size_t texture_count) {
  GpuTextureSlot g;
  g.texture = slot.texture >= 0 && static_cast<std::size_t>(slot.texture) < texture_count ? slot.texture : -1;
  g.texcoord = slot.texcoord == 1 ? 1u : 0u;
  g.sampler = std::uint32_t(slot.wrap_s) | (std::uint32_t(slot.wrap_t) << 2) | (std::uint32_t(slot.mag_filter) << 4) |
              (std::uint32_t(slot.min_filter) << 5) | (std::uint32_t(slot.mip_filter) << 6);
  g.area_scale = slot.transform.area_scale();
  g.row0 = glm::vec4(slot.transform.row0(), 0.0f);
  g.row1 = glm::vec4(slot.transform.row1(), 0.0f);
  return g;
}

// The mesh's vertices as the shaders read them, at `out` (positions.size() of them).
void write_vertices(const scene::Mesh& mesh, GpuVertex* out) {
  const std::size_t n = mesh.positions.size();
  const bool normals = mesh.normals.size() == n;
  const bool uvs = mesh.uvs.size() == n;
  const bool uvs1 = mesh.uvs1.size() == n;
  const bool tangents = mesh.tangents.size() == n;
  const bool colors = mesh.colors.size() == n;
  for (std::size_t v = 0; v < n; ++v) {
    const glm::vec2 uv = uvs ? mesh.uvs[v] : glm::vec2(0.0f);
    out[v] = {glm::vec4(mesh.positions[v], uv.x), glm::vec4(normals ? mesh.normals[v] : glm::vec3(0.0f), uv.y),
              tangents ? mesh.tangents[v] : glm::vec4(0.0f), colors ? mesh.colors[v] : glm::vec4(1.0f),
              glm::vec4(uvs1 ? mesh.uvs1[v] : glm::vec2(0.0f), 0.0f, 0.0f)};
  }
}

}  // namespace

std::vector<std::uint32_t> spatially_sorted_indices(const scene::Mesh& mesh) {
  const std::size_t n = mesh.triangle_count();
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const glm::vec3& p : mesh.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const glm::vec3 extent = glm::max(hi - lo, glm::vec3(1e-30f));
  std::vector<std::uint32_t> code(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint32_t* idx = &mesh.indices[k * 3];
    const glm::vec3 c = (mesh.positions[idx[0]] + mesh.positions[idx[1]] + mesh.positions[idx[2]]) / 3.0f;
    const glm::vec3 q = glm::clamp((c - lo) / extent, 0.0f, 1.0f) * 1023.0f;
    code[k] = spread_bits(std::uint32_t(q.x)) | (spread_bits(std::uint32_t(q.y)) << 1) |
              (spread_bits(std::uint32_t(q.z)) << 2);
  }
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return code[a] < code[b]; });
  std::vector<std::uint32_t> sorted;
  sorted.reserve(n * 3);
  for (std::uint32_t k : order) sorted.insert(sorted.end(), &mesh.indices[k * 3], &mesh.indices[k * 3] + 3);
  return sorted;
}

SceneLayout SceneLayout::build(const scene::Scene& s) {
  SceneLayout L;
  for (const scene::Mesh& mesh : s.meshes) {
    GpuMesh g;
    g.first_index = static_cast<std::uint32_t>(L.indices.size());
    g.first_vertex = static_cast<std::uint32_t>(L.vertices.size());
    g.triangle_count = static_cast<std::uint32_t>(mesh.triangle_count());
    g.material = static_cast<std::uint32_t>(L.materials.size());
    L.vertices.resize(L.vertices.size() + mesh.positions.size());
    write_vertices(mesh, L.vertices.data() + g.first_vertex);
    L.pose_versions.push_back(mesh.pose_version);
    const std::vector<std::uint32_t> sorted = spatially_sorted_indices(mesh);
    L.indices.insert(L.indices.end(), sorted.begin(), sorted.end());
    L.meshes.push_back(g);

    const scene::Material& m = s.material_of(mesh);
    GpuMaterial gm;
    gm.base_color = m.base_color;
    gm.emission_metallic = glm::vec4(m.emission(), m.metallic);
    gm.dielectric_f0_roughness = glm::vec4(m.dielectric_f0(), m.roughness);
    gm.specular = m.specular;
    gm.flags = (m.double_sided ? kMaterialDoubleSided : 0u) | (m.unlit ? kMaterialUnlit : 0u) |
               (m.alpha_mode == scene::AlphaMode::Mask ? kMaterialMask : 0u) |
               (m.alpha_mode == scene::AlphaMode::Blend ? kMaterialBlend : 0u);
    gm.alpha_cutoff = m.alpha_cutoff;
    gm.normal_scale = m.normal_scale;
    gm.base_color_texture = slot_of(m.base_color_texture, s.textures.size());
    gm.metallic_roughness_texture = slot_of(m.metallic_roughness_texture, s.textures.size());
    gm.normal_texture = slot_of(m.normal_texture, s.textures.size());
    gm.emissive_texture = slot_of(m.emissive_texture, s.textures.size());
    L.materials.push_back(gm);
  }

  L.deformed.assign(s.meshes.size(), false);
  for (const scene::DeformedMesh& d : s.deformed)
    if (d.mesh >= 0 && static_cast<std::size_t>(d.mesh) < s.meshes.size()) L.deformed[std::size_t(d.mesh)] = true;

  // The albedo table at its own nodes: x = cbrt(mu) and log(alpha) uniform over [0, 1]
  // (trace/specular_albedo.cpp), so bilinear interpolation on the GPU reproduces it.
  const auto& table = trace::DielectricSpecularAlbedo::get();
  std::vector<float> e, slope, e_avg, slope_avg;
  for (int r = 0; r < kAlbedoNodes; ++r) {
    const float y = float(r) / float(kAlbedoNodes - 1);
    const float alpha = std::pow(trace::Ggx::kMinAlpha, 1.0f - y);
    const float roughness = std::sqrt(alpha);
    for (int c = 0; c < kAlbedoNodes; ++c) {
      const float x = float(c) / float(kAlbedoNodes - 1);
      e.push_back(table.directional(x * x * x, roughness));
      slope.push_back(table.directional_slope(x * x * x, roughness));
    }
    e_avg.push_back(table.average(roughness));
    slope_avg.push_back(table.average_slope(roughness));
  }
  for (const auto* part : {&e, &slope, &e_avg, &slope_avg}) L.albedo.insert(L.albedo.end(), part->begin(), part->end());

  // The CPU tracer's mip chains, read back texel by texel through MipTexture's public lookup
  // (codes are exact: a texel decodes to code / 255), so both tracers filter the same texels.
  const trace::TextureSet set(s);
  for (std::size_t t = 0; t < set.size(); ++t) {
    const trace::MipTexture& tex = *set.get(static_cast<int>(t));
    GpuTexture g;
    g.first_level = static_cast<std::uint32_t>(L.texture_levels.size());
    g.levels = static_cast<std::uint32_t>(tex.levels());
    g.half_log2_texels = 0.5f * std::log2(float(tex.width(0)) * float(tex.height(0)));
    for (int level = 0; level < tex.levels(); ++level) {
      GpuTextureLevel l;
      l.offset = static_cast<std::uint32_t>(L.texels.size());
      l.width = static_cast<std::uint32_t>(tex.width(level));
      l.height = static_cast<std::uint32_t>(tex.height(level));
      L.texture_levels.push_back(l);
      for (int y = 0; y < tex.height(level); ++y)
        for (int x = 0; x < tex.width(level); ++x) {
          const glm::vec4 c = tex.texel(level, x, y, false) * 255.0f + 0.5f;
          L.texels.push_back(std::uint32_t(c.r) | (std::uint32_t(c.g) << 8) | (std::uint32_t(c.b) << 16) |
                             (std::uint32_t(c.a) << 24));
        }
    }
    L.textures.push_back(g);
  }

  if (s.environment_map) {
    // A black map lights nothing: it stays width 0, as the CPU tracer then samples nothing and
    // adds zero radiance.
    const trace::EnvironmentLight light(s.environment_map);
    const trace::EnvironmentTables t = light.tables();
    if (t.total > 0.0) {
      const scene::EnvironmentMap& map = light.map();
      L.environment = {static_cast<std::uint32_t>(t.width), static_cast<std::uint32_t>(t.height),
                       std::cos(map.rotation), std::sin(map.rotation)};
      const double texels = double(t.width) * double(t.height);
      for (int y = 0; y < t.height; ++y)
        for (int x = 0; x < t.width; ++x) {
          const std::size_t k = std::size_t(y) * std::size_t(t.width) + std::size_t(x);
          L.environment_texels.push_back(glm::vec4(map.texel(x, y), float(t.weights[k] * texels / t.total)));
        }
      L.environment_cdf.assign(t.row_cdf.begin(), t.row_cdf.end());
      L.environment_cdf.insert(L.environment_cdf.end(), t.column_cdf.begin(), t.column_cdf.end());
    }
  }

  L.place(s);
  return L;
}

std::vector<std::uint32_t> SceneLayout::repose(const scene::Scene& s) {
  std::vector<std::uint32_t> changed;
  for (std::size_t m = 0; m < meshes.size() && m < s.meshes.size(); ++m) {
    const scene::Mesh& mesh = s.meshes[m];
    if (!deformed[m] || mesh.pose_version == pose_versions[m]) continue;
    const std::uint32_t end = m + 1 < meshes.size() ? meshes[m + 1].first_vertex : std::uint32_t(vertices.size());
    if (mesh.positions.size() != end - meshes[m].first_vertex || mesh.triangle_count() != meshes[m].triangle_count)
      throw std::invalid_argument("SceneLayout::repose: mesh " + std::to_string(m) +
                                  " changed its vertex or triangle count");
    write_vertices(mesh, vertices.data() + meshes[m].first_vertex);
    pose_versions[m] = mesh.pose_version;
    changed.push_back(static_cast<std::uint32_t>(m));
  }
  return changed;
}

void SceneLayout::place(const scene::Scene& s) {
  instances.clear();
  emissive.clear();
  std::vector<double> power;
  for (const scene::Instance& inst : s.instances) {
    GpuInstance g;
    const trace::InstanceTransform xf = trace::InstanceTransform::from(inst.transform);
    g.object_to_world = xf.object_to_world;
    g.normal_matrix = glm::mat4(xf.normal_matrix);
    g.mesh = static_cast<std::uint32_t>(std::max(inst.mesh, 0));
    g.mirrored = xf.mirrored ? 1u : 0u;
    const bool valid = inst.mesh >= 0 && static_cast<std::size_t>(inst.mesh) < s.meshes.size();
    if (valid) {
      const scene::Mesh& mesh = s.meshes[static_cast<std::size_t>(inst.mesh)];
      const scene::Material& mat = s.material_of(mesh);
      if (mat.is_emissive() && mesh.triangle_count() > 0) {
        g.emissive_first = static_cast<std::int32_t>(emissive.size());
        // The triangles in the sorted order of the mesh's index range (the GPU's primitive ids).
        const GpuMesh& gm = meshes[static_cast<std::size_t>(inst.mesh)];
        const float front = xf.mirrored ? -1.0f : 1.0f;
        for (std::uint32_t k = 0; k < gm.triangle_count; ++k) {
          const std::uint32_t* idx = &indices[gm.first_index + 3 * k];
          auto world = [&](std::uint32_t i) { return glm::vec3(inst.transform * glm::vec4(mesh.positions[i], 1.0f)); };
          const glm::vec3 p0 = world(idx[0]), p1 = world(idx[1]), p2 = world(idx[2]);
          GpuEmissive t;
          const glm::vec3 c = glm::cross(p1 - p0, p2 - p0) * front;
          const float len = glm::length(c);
          const float area = std::isfinite(len) ? 0.5f * len : 0.0f;
          t.p0_area = glm::vec4(p0, area);
          t.e1_magnitude = glm::vec4(p1 - p0, std::max({trace::coordinate_magnitude(p0), trace::coordinate_magnitude(p1),
                                                         trace::coordinate_magnitude(p2)}));
          t.e2_double_sided = glm::vec4(p2 - p0, mat.double_sided ? 1.0f : 0.0f);
          t.normal_cdf = glm::vec4(area > 0.0f ? c / len : glm::vec3(0.0f, 0.0f, 1.0f), 0.0f);
          t.radiance_prob = glm::vec4(mat.emission(), 0.0f);
          t.instance = static_cast<std::uint32_t>(instances.size());
          t.prim = k;
          double p = double(area) * luminance(mat.emission()) * (mat.double_sided ? 2.0 : 1.0);
          power.push_back(std::isfinite(p) && p > 0.0 ? p : 0.0);
          emissive.push_back(t);
        }
      }
    }
    instances.push_back(g);
  }
  // The CDF normalised to 1, and each triangle's probability.
  const double total = std::accumulate(power.begin(), power.end(), 0.0);
  if (total > 0.0) {
    double running = 0.0;
    for (std::size_t k = 0; k < emissive.size(); ++k) {
      running += power[k];
      emissive[k].normal_cdf.w = k + 1 == emissive.size() ? 1.0f : float(running / total);
      emissive[k].radiance_prob.w = float(power[k] / total);
    }
  } else {
    emissive.clear();
    for (GpuInstance& g : instances) g.emissive_first = -1;
  }

  lights.clear();
  for (const scene::Light& light : s.lights) {
    GpuLight g;
    const float type = light.type == scene::LightType::Directional ? 0.0f
                       : light.type == scene::LightType::Point     ? 1.0f
                                                                   : 2.0f;
    g.position_type = glm::vec4(light.position, type);
    const float len = glm::length(light.direction);
    g.direction_range = glm::vec4(len > 0.0f ? light.direction / len : glm::vec3(0.0f), light.range);
    g.radiant = glm::vec4(len > 0.0f || light.type != scene::LightType::Directional ? light.radiant() : glm::vec3(0.0f), 0.0f);
    const float cos_outer = std::cos(light.outer_cone);
    const float cos_inner = std::cos(light.inner_cone);
    const float scale = 1.0f / std::max(1e-3f, cos_inner - cos_outer);
    g.spot = glm::vec4(scale, -cos_outer * scale, 0.0f, 0.0f);
    lights.push_back(g);
  }
}

}  // namespace ddish::trace_vk
