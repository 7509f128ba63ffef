// Private to the glTF loader: the pieces of gltf_loader.cpp that work on tinygltf's model,
// split into files by concept (accessors, meshes, materials/lights/cameras, animations).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "scene/load_error.h"
#include "scene/scene.h"

namespace ddish::scene::gltf {

struct Context {
  const tinygltf::Model& model;
  std::string file;  // reported in every error

  [[noreturn]] void fail(const std::string& problem) const { throw LoadError(file, problem); }
};

// An accessor read as floats, `components` per element (1..4, or 16 for MAT4). Normalised
// integer components are converted as glTF specifies; sparse accessors are applied.
struct FloatData {
  int components = 0;
  std::vector<float> values;  // count * components
  std::size_t count() const { return components ? values.size() / std::size_t(components) : 0; }
};

// Reads accessor `index` after checking that it and its buffer view lie inside their buffer.
// `what` names the use ("mesh 'Roof' POSITION") for the error message. Integer components that
// are not normalised are refused unless `integers` (skin joint indices), which reads their values.
FloatData read_floats(const Context& ctx, int index, const std::string& what, bool integers = false);
std::vector<std::uint32_t> read_indices(const Context& ctx, int index, const std::string& what);

// Meshes: one Scene::Mesh per triangle primitive; returns, for each glTF mesh, its Scene meshes.
std::vector<std::vector<int>> load_meshes(const Context& ctx, Scene& scene);

// The number of morph targets of node `node`'s mesh (the most of its primitives; 0 without).
std::size_t morph_target_count(const Context& ctx, int node);

// Skins (joints, inverse bind matrices) and the meshes they and morph targets deform: fills
// Scene::skins and Scene::deformed, after place(). A deformed mesh drawn by several nodes gets a
// copy per further node. Joint indices out of a skin's range fail the load.
void load_skins(const Context& ctx, Scene& scene);

void load_materials(const Context& ctx, Scene& scene);

// A KHR_lights_punctual light / a glTF camera as placed by node `node` (a light or camera used
// by several nodes becomes one Scene light or camera per node). Orthographic cameras are not
// supported: make_camera returns false and adds a warning.
Light make_light(const Context& ctx, int light, int node);
bool make_camera(const Context& ctx, int camera, int node, Scene& scene, Camera& out);

void load_animations(const Context& ctx, Scene& scene);

// EXT_mesh_gpu_instancing on node `node`: each instance's TRS as a matrix under the node (T * R *
// S, as glTF composes a node's), or nothing when the node has no such extension.
std::vector<glm::mat4> instance_transforms(const Context& ctx, int node);

// A number member of an extension object (`extensions[ext][key]`), or `fallback`.
double extension_number(const tinygltf::ExtensionMap& extensions, const std::string& ext,
                        const std::string& key, double fallback);

}  // namespace ddish::scene::gltf
