// glTF primitives to Scene meshes: triangle lists, strips and fans become indexed triangle
// lists; missing normals and tangents are generated; every index and every vertex value is
// checked, because the tracer and the rasterizer trust them blindly.
#include <cmath>

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
  return mesh;
}

}  // namespace

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
      if (!prim.targets.empty())
        scene.warnings.push_back("mesh '" + name + "': morph targets are ignored");
      meshes_of[i].push_back(int(scene.meshes.size()));
      scene.meshes.push_back(load_primitive(ctx, prim, name, scene.materials));
    }
  }
  return meshes_of;
}

}  // namespace ddish::scene::gltf
