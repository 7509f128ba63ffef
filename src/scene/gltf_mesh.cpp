// glTF primitives to Scene meshes: triangle lists, strips and fans become indexed triangle
// lists; missing normals and tangents are generated; every index and every vertex value is
// checked, because the tracer and the rasterizer trust them blindly.
#include <algorithm>
#include <cmath>

#include "io/host_memory.h"
#include "scene/gltf_internal.h"
#include "scene/tangents.h"

namespace ddish::scene::gltf {

namespace {

template <int N>
std::vector<glm::vec<N, float>> read_vectors(const Context& ctx, int accessor, std::size_t count,
                                             const std::string& what) {
  FloatData d = read_floats(ctx, accessor, what);
  if (d.components != N)
    ctx.fail(what + ": expected " + std::to_string(N) + " components, accessor " +
             std::to_string(accessor) + " has " + std::to_string(d.components));
  if (count != std::size_t(-1) && d.count() != count)
    ctx.fail(what + ": " + std::to_string(d.count()) + " values for " + std::to_string(count) +
             " vertices");
  std::vector<glm::vec<N, float>> out(d.count());
  for (std::size_t i = 0; i < out.size(); ++i)
    for (int c = 0; c < N; ++c) {
      float v = d.values[i * N + std::size_t(c)];
      if (!std::isfinite(v))
        ctx.fail(what + ": vertex " + std::to_string(i) + " is not finite (" + std::to_string(v) +
                 ")");
      out[i][c] = v;
    }
  return out;
}

// COLOR_0: RGB or RGBA, float or normalised unsigned byte / short (read_floats converts them);
// RGB gets alpha 1. Linear values, as glTF specifies.
std::vector<glm::vec4> read_colors(const Context& ctx, int accessor, std::size_t count,
                                   const std::string& what) {
  FloatData d = read_floats(ctx, accessor, what);
  if (d.components != 3 && d.components != 4)
    ctx.fail(what + ": expected 3 or 4 components, accessor " + std::to_string(accessor) +
             " has " + std::to_string(d.components));
  if (d.count() != count)
    ctx.fail(what + ": " + std::to_string(d.count()) + " values for " + std::to_string(count) +
             " vertices");
  const auto k = std::size_t(d.components);
  std::vector<glm::vec4> out(count, glm::vec4(1.0f));
  for (std::size_t i = 0; i < count; ++i)
    for (std::size_t c = 0; c < k; ++c) {
      float v = d.values[i * k + c];
      if (!std::isfinite(v))
        ctx.fail(what + ": vertex " + std::to_string(i) + " is not finite (" + std::to_string(v) +
                 ")");
      out[i][int(c)] = v;
    }
  return out;
}

bool morphed_attribute(const std::string& key) {
  return key == "POSITION" || key == "NORMAL" || key == "TANGENT";
}

// Morph targets: the deltas of POSITION, NORMAL and TANGENT, one per vertex, checked like the
// attributes they move. Other target attributes (texture coordinates, colours) are left out;
// load_meshes says so. Targets may share one accessor, so a small file can ask for targets ×
// vertices deltas: that product is checked against the memory available before any is read.
std::vector<MorphTarget> read_targets(const Context& ctx, const tinygltf::Primitive& prim,
                                      std::size_t n, const std::string& what) {
  std::uint64_t attributes = 0;
  for (const auto& target : prim.targets)
    for (const auto& entry : target) attributes += morphed_attribute(entry.first);
  const std::uint64_t bytes = attributes * std::uint64_t(n) * sizeof(glm::vec3);
  const std::uint64_t available = io::host_memory_available();
  if (bytes > available)
    ctx.fail(what + ": its " + std::to_string(prim.targets.size()) + " morph targets of " +
             std::to_string(n) + " vertices need " + io::format_bytes(bytes) + ", more than the " +
             io::format_bytes(available) + " of memory available");
  std::vector<MorphTarget> targets;
  for (std::size_t k = 0; k < prim.targets.size(); ++k) {
    const std::string tw = what + " morph target " + std::to_string(k);
    MorphTarget t;
    for (const auto& [key, accessor] : prim.targets[k]) {
      if (key == "POSITION")
        t.positions = read_vectors<3>(ctx, accessor, n, tw + " POSITION");
      else if (key == "NORMAL")
        t.normals = read_vectors<3>(ctx, accessor, n, tw + " NORMAL");
      else if (key == "TANGENT")
        t.tangents = read_vectors<3>(ctx, accessor, n, tw + " TANGENT");
    }
    targets.push_back(std::move(t));
  }
  return targets;
}

// JOINTS_n / WEIGHTS_n pairs for n = 0, 1, ...: joint indices are unsigned integers (bytes or
// shorts), weights floats or normalised integers, finite and not negative.
SkinInfluences read_influences(const Context& ctx, const tinygltf::Primitive& prim, std::size_t n,
                               const std::string& what) {
  std::vector<std::vector<glm::uvec4>> joints;
  std::vector<std::vector<glm::vec4>> weights;
  for (int set = 0;; ++set) {
    const std::string js = "JOINTS_" + std::to_string(set), ws = "WEIGHTS_" + std::to_string(set);
    const auto j = prim.attributes.find(js), w = prim.attributes.find(ws);
    if (j == prim.attributes.end() && w == prim.attributes.end()) break;
    if (j == prim.attributes.end() || w == prim.attributes.end())
      ctx.fail(what + ": " + (j == prim.attributes.end() ? ws + " without " + js : js + " without " + ws));
    FloatData jd = read_floats(ctx, j->second, what + " " + js, true);
    if (jd.components != 4 || jd.count() != n)
      ctx.fail(what + " " + js + ": expected " + std::to_string(n) + " VEC4 values, accessor " +
               std::to_string(j->second) + " has " + std::to_string(jd.count()) + " of " +
               std::to_string(jd.components) + " components");
    std::vector<glm::uvec4> jv(n);
    for (std::size_t i = 0; i < 4 * n; ++i) {
      const float v = jd.values[i];
      if (!(v >= 0.0f && v <= 65535.0f && v == std::floor(v)))
        ctx.fail(what + " " + js + ": vertex " + std::to_string(i / 4) +
                 " has a joint index that is not an unsigned integer (" + std::to_string(v) + ")");
      jv[i / 4][int(i % 4)] = unsigned(v);
    }
    std::vector<glm::vec4> wv = read_vectors<4>(ctx, w->second, n, what + " " + ws);
    for (std::size_t i = 0; i < n; ++i)
      if (glm::any(glm::lessThan(wv[i], glm::vec4(0.0f))))
        ctx.fail(what + " " + ws + ": vertex " + std::to_string(i) + " has a negative weight");
    joints.push_back(std::move(jv));
    weights.push_back(std::move(wv));
  }
  SkinInfluences out;
  out.sets = int(joints.size());
  out.joints.reserve(n * joints.size());
  out.weights.reserve(n * joints.size());
  for (std::size_t v = 0; v < n && out.sets > 0; ++v)
    for (std::size_t k = 0; k < joints.size(); ++k) {
      out.joints.push_back(joints[k][v]);
      out.weights.push_back(weights[k][v]);
    }
  return out;
}

// Triangle list indices for a primitive's mode; strips and fans keep a consistent winding.
std::vector<std::uint32_t> triangulate(const std::vector<std::uint32_t>& idx, int mode,
                                       const Context& ctx, const std::string& what) {
  std::vector<std::uint32_t> out;
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    if (idx.size() % 3 != 0)
      ctx.fail(what + ": " + std::to_string(idx.size()) +
               " indices is not a whole number of triangles");
    return idx;
  }
  for (std::size_t i = 0; i + 2 < idx.size(); ++i) {
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      bool odd = i % 2 == 1;
      out.insert(out.end(), {idx[i], idx[odd ? i + 2 : i + 1], idx[odd ? i + 1 : i + 2]});
    } else {  // fan around the first vertex
      out.insert(out.end(), {idx[i + 1], idx[i + 2], idx[0]});
    }
  }
  return out;
}

Mesh load_primitive(const Context& ctx, const tinygltf::Primitive& prim, const std::string& name,
                    const std::vector<Material>& materials) {
  const std::size_t material_count = materials.size();
  Mesh mesh;
  mesh.name = name;
  const std::string what = "mesh '" + name + "'";
  auto attr = [&](const char* key) {
    auto it = prim.attributes.find(key);
    return it == prim.attributes.end() ? -1 : it->second;
  };
  if (attr("POSITION") < 0) ctx.fail(what + ": primitive has no POSITION attribute");
  mesh.positions = read_vectors<3>(ctx, attr("POSITION"), std::size_t(-1), what + " POSITION");
  std::size_t n = mesh.positions.size();
  if (attr("NORMAL") >= 0) mesh.normals = read_vectors<3>(ctx, attr("NORMAL"), n, what + " NORMAL");
  if (attr("TEXCOORD_0") >= 0)
    mesh.uvs = read_vectors<2>(ctx, attr("TEXCOORD_0"), n, what + " TEXCOORD_0");
  else
    mesh.uvs.assign(n, glm::vec2(0.0f));
  if (attr("TEXCOORD_1") >= 0)
    mesh.uvs1 = read_vectors<2>(ctx, attr("TEXCOORD_1"), n, what + " TEXCOORD_1");
  else
    mesh.uvs1.assign(n, glm::vec2(0.0f));
  if (attr("COLOR_0") >= 0) mesh.colors = read_colors(ctx, attr("COLOR_0"), n, what + " COLOR_0");
  if (attr("TANGENT") >= 0)
    mesh.tangents = read_vectors<4>(ctx, attr("TANGENT"), n, what + " TANGENT");
  mesh.deformation.targets = read_targets(ctx, prim, n, what);
  mesh.deformation.influences = read_influences(ctx, prim, n, what);

  std::vector<std::uint32_t> idx;
  if (prim.indices >= 0) {
    idx = read_indices(ctx, prim.indices, what);
    for (std::size_t i = 0; i < idx.size(); ++i)
      if (idx[i] >= n)
        ctx.fail(what + ": index " + std::to_string(idx[i]) + " at position " + std::to_string(i) +
                 " is out of range (" + std::to_string(n) + " vertices)");
  } else {
    idx.resize(n);
    for (std::size_t i = 0; i < n; ++i) idx[i] = std::uint32_t(i);
  }
  int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
  mesh.indices = triangulate(idx, mode, ctx, what);

  if (prim.material >= 0 && std::size_t(prim.material) >= material_count)
    ctx.fail(what + ": material " + std::to_string(prim.material) + " does not exist");
  mesh.material = prim.material;

  mesh.deformation.generated_normals = mesh.normals.empty();
  if (mesh.normals.empty()) {
    generate_normals(mesh);
  } else {
    for (auto& nrm : mesh.normals) {
      float len = glm::length(nrm);
      nrm = len > 0.0f ? nrm / len : glm::vec3(0.0f, 1.0f, 0.0f);
    }
  }
  // MikkTSpace tangents on the UV set of the normal texture, as glTF specifies.
  if (mesh.tangents.empty())
    generate_tangents(
        mesh, mesh.material >= 0 ? materials[std::size_t(mesh.material)].normal_texture.texcoord : 0);
  for (const auto& p : mesh.positions) mesh.bounds.expand(p);
  if (!mesh.deformation.empty()) mesh.deformation.capture_rest(mesh);
  return mesh;
}

}  // namespace

std::size_t morph_target_count(const Context& ctx, int node) {
  const int mesh = ctx.model.nodes[std::size_t(node)].mesh;
  if (mesh < 0 || std::size_t(mesh) >= ctx.model.meshes.size()) return 0;
  std::size_t n = 0;
  for (const auto& prim : ctx.model.meshes[std::size_t(mesh)].primitives)
    n = std::max(n, prim.targets.size());
  return n;
}

std::vector<std::vector<int>> load_meshes(const Context& ctx, Scene& scene) {
  const auto& m = ctx.model;
  std::vector<std::vector<int>> meshes_of(m.meshes.size());
  for (std::size_t i = 0; i < m.meshes.size(); ++i) {
    const auto& gm = m.meshes[i];
    std::string base = gm.name.empty() ? "mesh" + std::to_string(i) : gm.name;
    for (std::size_t p = 0; p < gm.primitives.size(); ++p) {
      const auto& prim = gm.primitives[p];
      std::string name = gm.primitives.size() > 1 ? base + "#" + std::to_string(p) : base;
      int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
      if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
          mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        scene.warnings.push_back("mesh '" + name + "': points and lines are not rendered");
        continue;
      }
      for (std::size_t k = 0; k < prim.targets.size(); ++k)
        for (const auto& [key, accessor] : prim.targets[k])
          if (!morphed_attribute(key))
            scene.warnings.push_back("mesh '" + name + "' morph target " + std::to_string(k) +
                                     ": " + key + " is not morphed");
      meshes_of[i].push_back(int(scene.meshes.size()));
      scene.meshes.push_back(load_primitive(ctx, prim, name, scene.materials));
    }
  }
  return meshes_of;
}

}  // namespace ddish::scene::gltf
