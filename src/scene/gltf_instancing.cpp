// EXT_mesh_gpu_instancing: a node that draws its mesh once per instance, each with its own
// TRANSLATION / ROTATION / SCALE under the node. ddish expands the instances into scene
// Instances (Instance::local), so the tracer's BVH, the rasterizer's draws and every count see
// each of them, exactly as if the file had one node per instance.
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/gltf_internal.h"

namespace ddish::scene::gltf {

namespace {

// One attribute's accessor index, or -1 when the extension does not give it.
int attribute(const Context& ctx, const tinygltf::Value& attrs, const char* name,
              const std::string& what) {
  if (!attrs.Has(name)) return -1;
  const tinygltf::Value& v = attrs.Get(name);
  if (!v.IsInt() || v.GetNumberAsInt() < 0 ||
      std::size_t(v.GetNumberAsInt()) >= ctx.model.accessors.size())
    ctx.fail(what + ": attribute " + name + " is not an accessor of the file");
  return v.GetNumberAsInt();
}

// The values of one attribute: `components` floats per instance, all finite.
std::vector<float> attribute_values(const Context& ctx, int accessor, int components,
                                    const std::string& what) {
  FloatData d = read_floats(ctx, accessor, what);
  if (d.components != components)
    ctx.fail(what + ": expected " + std::to_string(components) + " components, got " +
             std::to_string(d.components));
  for (std::size_t i = 0; i < d.values.size(); ++i)
    if (!std::isfinite(d.values[i]))
      ctx.fail(what + ": instance " + std::to_string(i / std::size_t(components)) +
               " is not finite");
  return std::move(d.values);
}

}  // namespace

std::vector<glm::mat4> instance_transforms(const Context& ctx, int node) {
  const auto& gn = ctx.model.nodes[std::size_t(node)];
  auto it = gn.extensions.find("EXT_mesh_gpu_instancing");
  if (it == gn.extensions.end()) return {};
  const std::string what = "node " + std::to_string(node) + " EXT_mesh_gpu_instancing";
  if (!it->second.IsObject() || !it->second.Has("attributes") ||
      !it->second.Get("attributes").IsObject())
    ctx.fail(what + ": needs an \"attributes\" object");
  const tinygltf::Value& attrs = it->second.Get("attributes");
  const int t = attribute(ctx, attrs, "TRANSLATION", what);
  const int r = attribute(ctx, attrs, "ROTATION", what);
  const int s = attribute(ctx, attrs, "SCALE", what);
  if (t < 0 && r < 0 && s < 0) ctx.fail(what + ": no TRANSLATION, ROTATION or SCALE attribute");
  std::vector<float> tv, rv, sv;
  std::size_t count = std::size_t(-1);
  auto take = [&](int accessor, int components, const char* name, std::vector<float>& out) {
    if (accessor < 0) return;
    out = attribute_values(ctx, accessor, components, what + " " + name);
    const std::size_t n = out.size() / std::size_t(components);
    if (count != std::size_t(-1) && n != count)
      ctx.fail(what + ": attributes have different instance counts (" + std::to_string(count) +
               " and " + std::to_string(n) + ")");
    count = n;
  };
  take(t, 3, "TRANSLATION", tv);
  take(r, 4, "ROTATION", rv);
  take(s, 3, "SCALE", sv);
  std::vector<glm::mat4> out(count, glm::mat4(1.0f));
  for (std::size_t i = 0; i < count; ++i) {
    glm::mat4 m(1.0f);
    if (!tv.empty()) m = glm::translate(m, glm::vec3(tv[3 * i], tv[3 * i + 1], tv[3 * i + 2]));
    if (!rv.empty()) {
      const glm::quat q(rv[4 * i + 3], rv[4 * i], rv[4 * i + 1], rv[4 * i + 2]);  // file: xyzw
      if (glm::length(q) == 0.0f)
        ctx.fail(what + ": instance " + std::to_string(i) + " rotation is not a unit quaternion");
      m = m * glm::mat4_cast(glm::normalize(q));
    }
    if (!sv.empty()) m = glm::scale(m, glm::vec3(sv[3 * i], sv[3 * i + 1], sv[3 * i + 2]));
    out[i] = m;
  }
  return out;
}

}  // namespace ddish::scene::gltf
