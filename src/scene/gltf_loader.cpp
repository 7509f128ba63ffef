// glTF 2.0 files to the scene model. tinygltf (Debian's shared libtinygltf, which carries the
// implementation and its stb_image, so no TINYGLTF_IMPLEMENTATION here) parses the JSON and
// the buffers; everything it does not validate (accessor ranges, indices, finiteness, node
// hierarchy, required extensions) is checked here, so bad input becomes one LoadError.
#include "scene/gltf_loader.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <glm/gtc/matrix_transform.hpp>

#include "io/host_memory.h"
#include "scene/gltf_draco.h"
#include "scene/gltf_internal.h"
#include "scene/required_extensions.h"
#include "scene/sidecar.h"
#include "scene/memory_check.h"
#include "scene/texture_decode.h"

namespace ddish::scene {

namespace {

// The extensions ddish implements; a file that requires any other cannot be shown correctly.
bool supported_extension(const std::string& name) {
  return name == "KHR_lights_punctual" || name == "KHR_materials_emissive_strength" ||
         name == "EXT_mesh_gpu_instancing" || name == "KHR_materials_unlit" ||
         name == "KHR_texture_transform" || name == "KHR_materials_ior" ||
         name == "KHR_materials_specular" || name == "KHR_draco_mesh_compression";
}

LoadError unsupported_extension(const std::string& path, const std::string& ext) {
  return LoadError(path, "requires unsupported extension " + ext);
}

struct ImageCapture {
  const tinygltf::Model* model = nullptr;
  bool decode = true;
  std::vector<EncodedImage> images;  // kept for decoding (decode = true)
  std::vector<Texture> headers;      // sizes read at once (decode = false)
  std::vector<std::string> errors;
  std::vector<bool> seen;

  void resize(std::size_t n) {
    images.resize(n);
    headers.resize(n);
    errors.resize(n);
    seen.resize(n, false);
  }
};

// tinygltf image callback. Decoding keeps the encoded bytes so they are decoded later, once,
// in parallel; otherwise only the header is read here and the bytes are dropped at once.
// Images in buffer views are checked to lie inside their buffer before a byte is read,
// because tinygltf hands them over unchecked.
bool capture_image(tinygltf::Image* image, const int index, std::string* err, std::string*, int,
                   int, const unsigned char* bytes, int size, void* user) {
  auto* cap = static_cast<ImageCapture*>(user);
  if (index < 0) return false;
  if (image->bufferView >= 0) {
    const auto& m = *cap->model;
    const auto& view = m.bufferViews[std::size_t(image->bufferView)];
    const auto& data = m.buffers[std::size_t(view.buffer)].data;
    if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) {
      if (err) *err += "image " + std::to_string(index) + ": buffer view reaches past its buffer";
      return false;
    }
  }
  if (std::size_t(index) >= cap->seen.size()) cap->resize(std::size_t(index) + 1);
  std::size_t i = std::size_t(index);
  std::string name =
      !image->uri.empty() && image->uri.rfind("data:", 0) != 0 ? image->uri : image->name;
  cap->seen[i] = true;
  cap->images[i].name = name;
  cap->headers[i].name = name;
  std::size_t n = size > 0 ? std::size_t(size) : 0;
  if (cap->decode)
    cap->images[i].bytes.assign(bytes, bytes + n);
  else
    cap->errors[i] = read_image_header(bytes, n, cap->headers[i]);
  return true;
}

bool is_binary_gltf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[4] = {};
  in.read(magic, 4);
  return in.gcount() == 4 && std::memcmp(magic, "glTF", 4) == 0;
}

template <int N>
glm::vec<N, float> node_vector(const gltf::Context& ctx, const std::vector<double>& v,
                               glm::vec<N, float> fallback, const std::string& what) {
  if (v.empty()) return fallback;
  if (v.size() != std::size_t(N)) ctx.fail(what + " must have " + std::to_string(N) + " values");
  glm::vec<N, float> out;
  for (int i = 0; i < N; ++i) {
    out[i] = float(v[std::size_t(i)]);  // a finite double beyond float's range becomes Inf
    if (!std::isfinite(out[i])) ctx.fail(what + " is not finite");
  }
  return out;
}

// Splits a node matrix into TRS (glTF requires node matrices to be decomposable), because
// animations and pose() work on TRS.
void decompose(const glm::mat4& m, Node& node) {
  node.translation = glm::vec3(m[3]);
  glm::mat3 r(m);
  glm::vec3 s(glm::length(r[0]), glm::length(r[1]), glm::length(r[2]));
  if (glm::determinant(r) < 0.0f) s.x = -s.x;
  node.scale = s;
  if (s.x == 0.0f || s.y == 0.0f || s.z == 0.0f) return;  // collapsed: rotation is arbitrary
  r[0] /= s.x;
  r[1] /= s.y;
  r[2] /= s.z;
  node.rotation = glm::normalize(glm::quat_cast(r));
}

void load_nodes(const gltf::Context& ctx, const std::vector<std::vector<int>>& meshes_of,
                Scene& scene) {
  const auto& m = ctx.model;
  scene.nodes.resize(m.nodes.size());
  for (std::size_t i = 0; i < m.nodes.size(); ++i) {
    const auto& gn = m.nodes[i];
    Node& node = scene.nodes[i];
    node.name = gn.name.empty() ? "node" + std::to_string(i) : gn.name;
    const std::string what = "node '" + node.name + "'";
    if (!gn.matrix.empty()) {
      if (gn.matrix.size() != 16) ctx.fail(what + ": matrix must have 16 values");
      glm::mat4 mat;
      for (int k = 0; k < 16; ++k) {
        mat[k / 4][k % 4] = float(gn.matrix[std::size_t(k)]);
        if (!std::isfinite(mat[k / 4][k % 4])) ctx.fail(what + ": matrix is not finite");
      }
      decompose(mat, node);
    } else {
      node.translation =
          node_vector<3>(ctx, gn.translation, glm::vec3(0.0f), what + " translation");
      glm::vec4 q = node_vector<4>(ctx, gn.rotation, glm::vec4(0, 0, 0, 1), what + " rotation");
      if (glm::length(q) == 0.0f) ctx.fail(what + ": rotation is not a unit quaternion");
      q = glm::normalize(q);
      node.rotation = glm::quat(q.w, q.x, q.y, q.z);
      node.scale = node_vector<3>(ctx, gn.scale, glm::vec3(1.0f), what + " scale");
    }
    for (int c : gn.children) {
      if (c < 0 || std::size_t(c) >= m.nodes.size())
        ctx.fail(what + ": child node " + std::to_string(c) + " does not exist");
      if (scene.nodes[std::size_t(c)].parent >= 0 || std::size_t(c) == i)
        ctx.fail("node " + std::to_string(c) +
                 " has more than one parent (the hierarchy must be a tree)");
      scene.nodes[std::size_t(c)].parent = int(i);
      node.children.push_back(c);
    }
    if (gn.mesh >= 0) {
      if (std::size_t(gn.mesh) >= m.meshes.size())
        ctx.fail(what + ": mesh " + std::to_string(gn.mesh) + " does not exist");
      node.meshes = meshes_of[std::size_t(gn.mesh)];
    }
    if (gn.skin >= 0) {
      if (std::size_t(gn.skin) >= m.skins.size())
        ctx.fail(what + ": skin " + std::to_string(gn.skin) + " does not exist");
      node.skin = gn.skin;
    }
    // Morph weights: the node's, else its mesh's, else 0 (missing ones are 0 too).
    if (const std::size_t targets = gltf::morph_target_count(ctx, int(i)); targets > 0) {
      const std::vector<double>& w =
          !gn.weights.empty() ? gn.weights : m.meshes[std::size_t(gn.mesh)].weights;
      node.weights.assign(targets, 0.0f);
      for (std::size_t k = 0; k < std::min(targets, w.size()); ++k) {
        node.weights[k] = float(w[k]);
        if (!std::isfinite(node.weights[k])) ctx.fail(what + ": morph weight " + std::to_string(k) + " is not finite");
      }
    }
  }
  // With one parent each, a node that no walk down from a parentless node reaches is on a
  // cycle; pose() would never place it, so such a file is rejected.
  std::vector<bool> reached(scene.nodes.size(), false);
  std::vector<int> stack;
  for (std::size_t i = 0; i < scene.nodes.size(); ++i)
    if (scene.nodes[i].parent < 0) stack.push_back(int(i));
  while (!stack.empty()) {
    int n = stack.back();
    stack.pop_back();
    reached[std::size_t(n)] = true;
    for (int c : scene.nodes[std::size_t(n)].children) stack.push_back(c);
  }
  for (std::size_t i = 0; i < reached.size(); ++i)
    if (!reached[i])
      ctx.fail("node " + std::to_string(i) + " is part of a cycle (the hierarchy must be a tree)");
}

// Instances, lights and cameras of the nodes reachable from the scene's roots.
void place(const gltf::Context& ctx, Scene& scene) {
  const auto& m = ctx.model;
  if (!m.scenes.empty()) {
    int s = m.defaultScene >= 0 ? m.defaultScene : 0;
    if (std::size_t(s) >= m.scenes.size())
      ctx.fail("default scene " + std::to_string(s) + " does not exist");
    for (int n : m.scenes[std::size_t(s)].nodes) {
      if (n < 0 || std::size_t(n) >= scene.nodes.size())
        ctx.fail("scene node " + std::to_string(n) + " does not exist");
      if (scene.nodes[std::size_t(n)].parent >= 0)
        ctx.fail("scene node " + std::to_string(n) + " is not a root node");
      scene.roots.push_back(n);
    }
  } else {
    for (std::size_t n = 0; n < scene.nodes.size(); ++n)
      if (scene.nodes[n].parent < 0) scene.roots.push_back(int(n));
  }
  std::vector<int> stack(scene.roots.rbegin(), scene.roots.rend());
  while (!stack.empty()) {
    int n = stack.back();
    stack.pop_back();
    Node& node = scene.nodes[std::size_t(n)];
    const std::vector<glm::mat4> gpu_instances = gltf::instance_transforms(ctx, n);
    if (gpu_instances.empty())
      for (int mesh : node.meshes) scene.instances.push_back(Instance{mesh, n, glm::mat4(1.0f)});
    for (const glm::mat4& local : gpu_instances)
      for (int mesh : node.meshes)
        scene.instances.push_back(Instance{mesh, n, glm::mat4(1.0f), local});
    const auto& gn = m.nodes[std::size_t(n)];
    if (gn.camera >= 0) {
      Camera cam;
      if (gltf::make_camera(ctx, gn.camera, n, scene, cam)) {
        node.camera = int(scene.cameras.size());
        scene.cameras.push_back(cam);
      }
    }
    double light = gltf::extension_number(gn.extensions, "KHR_lights_punctual", "light", -1.0);
    if (light >= 0.0) {
      node.light = int(scene.lights.size());
      scene.lights.push_back(gltf::make_light(ctx, int(light), n));
    }
    for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) stack.push_back(*it);
  }
}

}  // namespace

Scene load_scene(const std::string& path, const LoadOptions& options) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw LoadError(path, "no such file");
  if (!std::filesystem::is_regular_file(path, ec)) throw LoadError(path, "not a regular file");
  const std::uintmax_t file_bytes = std::filesystem::file_size(path, ec);
  if (!ec) check_file_fits(path, file_bytes, io::host_memory_available());

  tinygltf::Model model;
  ImageCapture capture;
  capture.model = &model;
  capture.decode = options.decode_textures;
  tinygltf::TinyGLTF parser;
  parser.SetImageLoader(&capture_image, &capture);
  std::string err, warn;
  bool ok = false;
  try {
    ok = gltf::read_gltf(parser, model, err, warn, path, is_binary_gltf(path));
  } catch (const std::exception& e) {
    throw LoadError(path, std::string("not a valid glTF file (") + e.what() + ")");
  }
  if (!ok) {
    // A required extension tinygltf cannot read either (Draco's accessors have no buffer view)
    // is the reason to give, not the accessor error it stumbled on.
    for (const std::string& ext : required_extensions(path))
      if (!supported_extension(ext)) throw unsupported_extension(path, ext);
    throw LoadError(path, err.empty() ? "not a valid glTF file" : err);
  }
  if (model.asset.version.rfind("2.", 0) != 0)
    throw LoadError(path, "glTF version '" + model.asset.version + "' is not 2.x");
  for (const auto& ext : model.extensionsRequired)
    if (!supported_extension(ext)) throw unsupported_extension(path, ext);

  Scene scene;
  scene.path = path;
  gltf::decode_draco(model, path, scene.warnings);  // before anything reads an accessor
  gltf::Context ctx{model, path};
  // Optional extensions ddish does not implement are ignored, as glTF allows, but said so.
  for (const auto& ext : model.extensionsUsed)
    if (!supported_extension(ext))
      scene.warnings.push_back("extension " + ext + " is not supported and is ignored");
  capture.resize(model.images.size());
  for (std::size_t i = 0; i < model.images.size(); ++i) {
    if (!capture.seen[i])
      ctx.fail("image " + std::to_string(i) + " '" + model.images[i].uri + "' cannot be read");
    if (!capture.errors[i].empty())
      ctx.fail("image " + std::to_string(i) + " '" + capture.headers[i].name +
               "': " + capture.errors[i]);
  }
  if (options.decode_textures) {
    check_textures_fit(path, decode_textures(capture.images, false, 1, path),
                       io::host_memory_available());
    scene.textures = decode_textures(capture.images, true, options.decode_threads, path);
  }
  else
    scene.textures = std::move(capture.headers);
  gltf::load_materials(ctx, scene);
  std::vector<std::vector<int>> meshes_of = gltf::load_meshes(ctx, scene);
  load_nodes(ctx, meshes_of, scene);
  place(ctx, scene);
  gltf::load_skins(ctx, scene);
  gltf::load_animations(ctx, scene);

  if (options.read_sidecar) {
    scene.sidecar = load_sidecar(path);
    if (!scene.sidecar.camera.empty() && !scene.find_camera(scene.sidecar.camera))
      throw LoadError(sidecar_path(path), "camera '" + scene.sidecar.camera + "' is not in " +
                                              std::filesystem::path(path).filename().string());
  }
  // glTF's candela (point, spot) and lux (directional) become W/sr and W/m^2.
  if (scene.sidecar.light_units == LightUnits::Photometric)
    for (Light& light : scene.lights) light.intensity /= kLumensPerWatt;
  scene.pose(0.0);
  return scene;
}

}  // namespace ddish::scene
