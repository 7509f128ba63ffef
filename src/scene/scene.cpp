#include "scene/scene.h"

#include <algorithm>

#include <glm/gtc/matrix_transform.hpp>

namespace ddish::scene {

namespace {

glm::mat4 local_matrix(const Node& n) {
  return glm::translate(glm::mat4(1.0f), n.translation) * glm::mat4_cast(n.rotation) *
         glm::scale(glm::mat4(1.0f), n.scale);
}

void apply(const AnimChannel& ch, float t, std::vector<Node>& nodes) {
  if (ch.node < 0 || std::size_t(ch.node) >= nodes.size()) return;
  Node& n = nodes[std::size_t(ch.node)];
  if (ch.path == AnimPath::Weights) {
    n.weights.resize(std::size_t(ch.width));
    ch.sample(t, n.weights);
    return;
  }
  glm::vec4 v = ch.sample(t);
  switch (ch.path) {
    case AnimPath::Translation:
      n.translation = glm::vec3(v);
      break;
    case AnimPath::Rotation:
      n.rotation = glm::quat(v.w, v.x, v.y, v.z);
      break;
    case AnimPath::Scale:
      n.scale = glm::vec3(v);
      break;
    case AnimPath::Weights:
      break;
  }
}

// Poses a deformed mesh for its node's weights and skin; true when its vertices changed.
bool pose_deformed(DeformedMesh& d, Scene& scene) {
  const Node& node = scene.nodes[std::size_t(d.node)];
  std::vector<glm::mat4> joints;
  if (d.skin >= 0) {
    const Skin& skin = scene.skins[std::size_t(d.skin)];
    // A collapsed node (scale 0) has no inverse; its instance transform collapses the mesh anyway.
    const glm::mat4 inverse_world =
        glm::determinant(node.world) != 0.0f ? glm::inverse(node.world) : glm::mat4(1.0f);
    joints.reserve(skin.joints.size());
    for (std::size_t j = 0; j < skin.joints.size(); ++j)
      joints.push_back(joint_matrix(inverse_world, scene.nodes[std::size_t(skin.joints[j])].world,
                                    skin.inverse_bind[j]));
  }
  if (d.posed && d.weights == node.weights && d.joints == joints) return false;
  d.weights = node.weights;
  d.joints = std::move(joints);
  d.posed = true;
  Mesh& mesh = scene.meshes[std::size_t(d.mesh)];
  pose_mesh(mesh, d.weights, d.joints);
  ++mesh.pose_version;
  return true;
}

}  // namespace

std::vector<int> Scene::pose(double t) {
  time = t;
  for (const auto& anim : animations)
    for (const auto& ch : anim.channels) apply(ch, float(t), nodes);

  // Parents before children: walk down from every node without a parent.
  std::vector<std::pair<int, glm::mat4>> stack;
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].parent < 0) stack.emplace_back(int(i), glm::mat4(1.0f));
  while (!stack.empty()) {
    auto [n, parent_world] = stack.back();
    stack.pop_back();
    Node& node = nodes[std::size_t(n)];
    node.world = parent_world * local_matrix(node);
    for (int c : node.children) stack.emplace_back(c, node.world);
  }

  std::vector<bool> reshaped(meshes.size(), false);
  for (DeformedMesh& d : deformed)
    if (pose_deformed(d, *this)) reshaped[std::size_t(d.mesh)] = true;

  std::vector<int> moved;
  for (std::size_t i = 0; i < instances.size(); ++i) {
    Instance& inst = instances[i];
    const glm::mat4 world = nodes[std::size_t(inst.node)].world * inst.local;
    const bool changed = world != inst.transform;
    if (changed) inst.transform = world;
    if (changed || (inst.mesh >= 0 && reshaped[std::size_t(inst.mesh)])) moved.push_back(int(i));
  }
  for (Light& light : lights) {
    const glm::mat4& w = nodes[std::size_t(light.node)].world;
    light.position = glm::vec3(w[3]);
    glm::vec3 d = glm::mat3(w) * glm::vec3(0.0f, 0.0f, -1.0f);
    if (glm::length(d) > 0.0f) light.direction = glm::normalize(d);
  }
  for (Camera& cam : cameras) {
    if (cam.node < 0) continue;  // placed by ddish (the framing camera), not by the hierarchy
    const glm::mat4& w = nodes[std::size_t(cam.node)].world;
    cam.eye = glm::vec3(w[3]);
    glm::vec3 f = glm::mat3(w) * glm::vec3(0.0f, 0.0f, -1.0f);
    glm::vec3 u = glm::mat3(w) * glm::vec3(0.0f, 1.0f, 0.0f);
    if (glm::length(f) > 0.0f) cam.forward = glm::normalize(f);
    if (glm::length(u) > 0.0f) cam.up = glm::normalize(u);
  }
  return moved;
}

double Scene::animation_duration() const {
  double d = 0.0;
  for (const auto& a : animations) d = std::max(d, double(a.duration()));
  return d;
}

Aabb Scene::bounds() const {
  Aabb box;
  for (const auto& inst : instances)
    box.expand(meshes[std::size_t(inst.mesh)].bounds.transformed(inst.transform));
  return box;
}

std::size_t Scene::triangle_count() const {
  std::size_t n = 0;
  for (const auto& inst : instances) n += meshes[std::size_t(inst.mesh)].triangle_count();
  return n;
}

const Material& Scene::material_of(const Mesh& mesh) const {
  static const Material default_material{};  // glTF's default: white, metallic 1, roughness 1
  if (mesh.material < 0 || std::size_t(mesh.material) >= materials.size()) return default_material;
  return materials[std::size_t(mesh.material)];
}

const Camera* Scene::find_camera(const std::string& name) const {
  for (const auto& c : cameras)
    if (c.name == name) return &c;
  return nullptr;
}

const Camera* Scene::default_camera() const {
  if (!sidecar.camera.empty())
    if (const Camera* c = find_camera(sidecar.camera)) return c;
  return cameras.empty() ? nullptr : &cameras.front();
}

}  // namespace ddish::scene
