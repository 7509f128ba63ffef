// glTF skins, and which meshes pose() deforms. A skin's joints must be nodes of the file and its
// inverse bind matrices finite, one per joint; a skinned vertex may use only the skin's joints
// (any weight above 0 on another is an error: there is no sensible place to put the vertex).
// A mesh is deformed where it has morph targets, or skin influences and a node with a skin
// draws it. Its pose depends on that node, so a second node drawing it gets its own copy.
#include <cmath>
#include <map>
#include <utility>

#include "scene/gltf_internal.h"

namespace ddish::scene::gltf {

namespace {

Skin read_skin(const Context& ctx, std::size_t index) {
  const tinygltf::Skin& gs = ctx.model.skins[index];
  Skin skin;
  skin.name = gs.name.empty() ? "skin" + std::to_string(index) : gs.name;
  const std::string what = "skin '" + skin.name + "'";
  if (gs.joints.empty()) ctx.fail(what + ": has no joints (glTF requires at least one)");
  for (int j : gs.joints) {
    if (j < 0 || std::size_t(j) >= ctx.model.nodes.size())
      ctx.fail(what + ": joint node " + std::to_string(j) + " does not exist");
    skin.joints.push_back(j);
  }
  skin.inverse_bind.assign(skin.joints.size(), glm::mat4(1.0f));
  if (gs.inverseBindMatrices >= 0) {
    FloatData d = read_floats(ctx, gs.inverseBindMatrices, what + " inverseBindMatrices");
    if (d.components != 16 || d.count() < skin.joints.size())
      ctx.fail(what + ": inverseBindMatrices holds " + std::to_string(d.count()) + " values of " +
               std::to_string(d.components) + " components, expected " +
               std::to_string(skin.joints.size()) + " MAT4");
    for (std::size_t j = 0; j < skin.joints.size(); ++j)
      for (int k = 0; k < 16; ++k) {
        const float v = d.values[16 * j + std::size_t(k)];
        if (!std::isfinite(v))
          ctx.fail(what + ": inverse bind matrix " + std::to_string(j) + " is not finite");
        skin.inverse_bind[j][k / 4][k % 4] = v;  // column-major, as glTF stores it
      }
  }
  return skin;
}

}  // namespace

void load_skins(const Context& ctx, Scene& scene) {
  for (std::size_t s = 0; s < ctx.model.skins.size(); ++s) scene.skins.push_back(read_skin(ctx, s));

  std::vector<int> owner(scene.meshes.size(), -1);  // the node a deformed mesh is posed for
  std::map<std::pair<int, int>, int> copies;        // (mesh, node) -> the node's copy
  for (Instance& inst : scene.instances) {
    if (inst.mesh < 0) continue;
    const Node& node = scene.nodes[std::size_t(inst.node)];
    const Mesh& mesh = scene.meshes[std::size_t(inst.mesh)];
    const bool has_influences = !mesh.deformation.influences.empty();
    const bool skinned = node.skin >= 0 && has_influences;
    if (node.skin >= 0 && !has_influences && owner[std::size_t(inst.mesh)] == -1) {
      scene.warnings.push_back("node '" + node.name + "': mesh '" + mesh.name +
                               "' has no JOINTS_0 / WEIGHTS_0, so its skin does not move it");
    }
    if (!skinned && mesh.deformation.targets.empty()) continue;
    if (skinned) {
      const Skin& skin = scene.skins[std::size_t(node.skin)];
      const std::string problem = check_influences(mesh.deformation.influences, skin.joints.size());
      if (!problem.empty())
        ctx.fail("node '" + node.name + "' mesh '" + mesh.name + "' skin '" + skin.name + "': " +
                 problem);
    }
    int& own = owner[std::size_t(inst.mesh)];
    if (own == -1 || own == inst.node) {
      if (own == -1) scene.deformed.push_back({inst.mesh, inst.node, skinned ? node.skin : -1});
      own = inst.node;
      continue;
    }
    // Another node already poses this mesh: this node draws its own copy.
    const std::pair<int, int> key{inst.mesh, inst.node};
    auto it = copies.find(key);
    if (it == copies.end()) {
      const int copy = int(scene.meshes.size());
      scene.meshes.push_back(scene.meshes[std::size_t(inst.mesh)]);
      owner.push_back(inst.node);
      scene.deformed.push_back({copy, inst.node, skinned ? node.skin : -1});
      it = copies.emplace(key, copy).first;
    }
    inst.mesh = it->second;
  }
  // The nodes' mesh lists follow their copies.
  for (const auto& [key, copy] : copies)
    for (int& m : scene.nodes[std::size_t(key.second)].meshes)
      if (m == key.first) m = copy;
}

}  // namespace ddish::scene::gltf
