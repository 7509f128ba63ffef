#include "scene/gltf_draco.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>

#include <draco/compression/decode.h>
#include <draco/mesh/mesh.h>
#include <nlohmann/json.hpp>

#include "io/child_process.h"
#include "scene/load_error.h"

namespace ddish::scene::gltf {

namespace {

constexpr const char* kDraco = "KHR_draco_mesh_compression";

using nlohmann::json;

bool uses_draco(const json& j) {
  for (const char* list : {"extensionsUsed", "extensionsRequired"})
    if (j.contains(list) && j[list].is_array())
      for (const json& e : j[list])
        if (e.is_string() && e.get<std::string>() == kDraco) return true;
  return false;
}

// Points each Draco primitive's indices accessor that has no buffer view at the primitive's
// Draco buffer view, so that tinygltf's check passes; decode_draco replaces it.
void patch_indices(json& j) {
  if (!j.contains("meshes") || !j["meshes"].is_array() || !j.contains("accessors") ||
      !j["accessors"].is_array())
    return;
  json& accessors = j["accessors"];
  for (json& mesh : j["meshes"]) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (json& prim : mesh["primitives"]) {
      if (!prim.is_object() || !prim.contains("extensions") || !prim["extensions"].is_object() ||
          !prim["extensions"].contains(kDraco) || !prim.contains("indices") ||
          !prim["indices"].is_number_integer())
        continue;
      const json& ext = prim["extensions"][kDraco];
      if (!ext.is_object() || !ext.contains("bufferView") || !ext["bufferView"].is_number_integer())
        continue;
      const auto index = prim["indices"].get<std::int64_t>();
      if (index < 0 || index >= static_cast<std::int64_t>(accessors.size())) continue;
      json& acc = accessors[static_cast<std::size_t>(index)];
      if (acc.is_object() && !acc.contains("bufferView")) acc["bufferView"] = ext["bufferView"];
    }
  }
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::uint32_t u32(const std::string& b, std::size_t at) {
  std::uint32_t v = 0;
  std::memcpy(&v, b.data() + at, 4);
  return v;
}

void put_u32(std::string& b, std::uint32_t v) {
  char c[4];
  std::memcpy(c, &v, 4);
  b.append(c, 4);
}

std::string base_dir(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash);
}

std::string fmt_seconds(std::chrono::milliseconds ms) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f s", static_cast<double>(ms.count()) / 1000.0);
  return text;
}

template <typename T>
void append_values(const draco::PointAttribute& attr, const draco::Mesh& mesh, int components,
                   std::vector<unsigned char>& out) {
  const std::size_t bytes = sizeof(T) * static_cast<std::size_t>(components);
  out.resize(static_cast<std::size_t>(mesh.num_points()) * bytes);
  T value[4] = {};
  for (draco::PointIndex i(0); i < mesh.num_points(); ++i) {
    attr.ConvertValue<T>(attr.mapped_index(i), static_cast<std::int8_t>(components), value);
    std::memcpy(out.data() + static_cast<std::size_t>(i.value()) * bytes, value, bytes);
  }
}

int add_buffer(tinygltf::Model& model, std::vector<unsigned char> data) {
  tinygltf::Buffer buffer;
  buffer.data = std::move(data);
  tinygltf::BufferView view;
  view.buffer = static_cast<int>(model.buffers.size());
  view.byteOffset = 0;
  view.byteLength = buffer.data.size();
  view.byteStride = 0;
  model.buffers.push_back(std::move(buffer));
  model.bufferViews.push_back(view);
  return static_cast<int>(model.bufferViews.size()) - 1;
}

void point_at(tinygltf::Accessor& acc, int view, std::size_t count) {
  acc.bufferView = view;
  acc.byteOffset = 0;
  acc.count = count;
  acc.sparse.isSparse = false;
}

// One primitive's decoded arrays: 32-bit indices, and the values of each compressed attribute
// in its accessor's component type, keyed by accessor.
struct DecodedPrimitive {
  std::vector<unsigned char> indices;
  std::size_t points = 0;
  std::vector<std::pair<int, std::vector<unsigned char>>> attributes;
};

// Decodes one primitive's Draco data (the view was checked by compressed_bytes); throws
// std::runtime_error with the reason. Runs in a child process (decode_with_deadline).
DecodedPrimitive decode_arrays(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                               const tinygltf::Value& ext, const unsigned char* bytes, std::size_t size) {
  draco::DecoderBuffer in;
  in.Init(reinterpret_cast<const char*>(bytes), size);
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&in);
  if (!decoded.ok())
    throw std::runtime_error("the Draco data cannot be decoded (" +
                             decoded.status().error_msg_string() + ")");
  const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  if (!mesh) throw std::runtime_error("the Draco data holds no mesh");

  DecodedPrimitive out;
  out.points = mesh->num_points();
  out.indices.resize(static_cast<std::size_t>(mesh->num_faces()) * 3 * 4);
  for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = mesh->face(f)[k].value();
      std::memcpy(out.indices.data() + (static_cast<std::size_t>(f.value()) * 3 + k) * 4, &v, 4);
    }
  for (const auto& [name, id] : ext.Get("attributes").Get<tinygltf::Value::Object>()) {
    const auto it = prim.attributes.find(name);
    if (it == prim.attributes.end())
      throw std::runtime_error("attribute " + name + " is compressed but not in the primitive");
    if (!id.IsInt() || id.Get<int>() < 0)
      throw std::runtime_error("attribute " + name + " has no Draco id");
    if (it->second < 0 || static_cast<std::size_t>(it->second) >= model.accessors.size())
      throw std::runtime_error("attribute " + name + ": accessor " + std::to_string(it->second) +
                               " does not exist");
    const draco::PointAttribute* attr =
        mesh->GetAttributeByUniqueId(static_cast<std::uint32_t>(id.Get<int>()));
    if (!attr)
      throw std::runtime_error("attribute " + name + ": the Draco data has no attribute " +
                               std::to_string(id.Get<int>()));
    const tinygltf::Accessor& acc = model.accessors[static_cast<std::size_t>(it->second)];
    const int components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(acc.type));
    if (components < 1 || components > 4 || attr->num_components() != components)
      throw std::runtime_error("attribute " + name + ": " + std::to_string(attr->num_components()) +
                               " Draco components for an accessor of " + std::to_string(components));
    std::vector<unsigned char> values;
    switch (acc.componentType) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: append_values<float>(*attr, *mesh, components, values); break;
      case TINYGLTF_COMPONENT_TYPE_BYTE: append_values<std::int8_t>(*attr, *mesh, components, values); break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: append_values<std::uint8_t>(*attr, *mesh, components, values); break;
      case TINYGLTF_COMPONENT_TYPE_SHORT: append_values<std::int16_t>(*attr, *mesh, components, values); break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: append_values<std::uint16_t>(*attr, *mesh, components, values); break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: append_values<std::uint32_t>(*attr, *mesh, components, values); break;
      default:
        throw std::runtime_error("attribute " + name + ": component type " +
                                 std::to_string(acc.componentType) + " is not a glTF vertex type");
    }
    out.attributes.emplace_back(it->second, std::move(values));
  }
  return out;
}

// The child's answer: [u64 points][u64 index bytes][indices] then per attribute
// [i64 accessor][u64 bytes][values]. Read back with every length checked against what is left.
void put_u64(std::string& b, std::uint64_t v) { b.append(reinterpret_cast<const char*>(&v), 8); }

std::string serialize(const DecodedPrimitive& d) {
  std::string b;
  put_u64(b, d.points);
  put_u64(b, d.indices.size());
  b.append(reinterpret_cast<const char*>(d.indices.data()), d.indices.size());
  for (const auto& [accessor, values] : d.attributes) {
    put_u64(b, static_cast<std::uint64_t>(static_cast<std::int64_t>(accessor)));
    put_u64(b, values.size());
    b.append(reinterpret_cast<const char*>(values.data()), values.size());
  }
  return b;
}

DecodedPrimitive deserialize(const std::string& b) {
  std::size_t at = 0;
  const auto take = [&](std::size_t n) {
    if (n > b.size() - at) throw std::runtime_error("the Draco decoder's answer is truncated");
    const char* p = b.data() + at;
    at += n;
    return p;
  };
  const auto u64 = [&] {
    std::uint64_t v = 0;
    std::memcpy(&v, take(8), 8);
    return v;
  };
  const auto bytes = [&](std::uint64_t n) {
    const auto* p = reinterpret_cast<const unsigned char*>(take(static_cast<std::size_t>(n)));
    return std::vector<unsigned char>(p, p + n);
  };
  DecodedPrimitive d;
  d.points = static_cast<std::size_t>(u64());
  d.indices = bytes(u64());
  while (at < b.size()) {
    const auto accessor = static_cast<int>(static_cast<std::int64_t>(u64()));
    d.attributes.emplace_back(accessor, bytes(u64()));
  }
  return d;
}

// The decoder gets kDecodeBase plus kDecodePerMiB for each MiB of compressed data. Measured:
// Sponza transcoded to Draco (262k triangles, 44 primitives, 378 KB of Draco data) costs 0.37 s
// of CPU more to load than the plain file, forks included, so about 1 s of CPU per MiB: the
// limit leaves 10x for a loaded machine or a sanitizer build, while a hostile 1 KB stream is
// stopped after 2 s.
constexpr std::chrono::milliseconds kDecodeBase{2000};
constexpr std::chrono::milliseconds kDecodePerMiB{10000};

DecodedPrimitive decode_with_deadline(const tinygltf::Model& model, const tinygltf::Primitive& prim,
                                      const tinygltf::Value& ext, const unsigned char* bytes,
                                      std::size_t size) {
  const auto limit = kDecodeBase + std::chrono::milliseconds(static_cast<long long>(
                                       static_cast<double>(kDecodePerMiB.count()) *
                                       static_cast<double>(size) / (1 << 20)));
  const io::ChildOutcome outcome = io::run_in_child(
      [&] { return serialize(decode_arrays(model, prim, ext, bytes, size)); }, limit);
  switch (outcome.status) {
    case io::ChildOutcome::Status::kOk: return deserialize(outcome.bytes);
    case io::ChildOutcome::Status::kFailed: throw std::runtime_error(outcome.bytes);
    case io::ChildOutcome::Status::kTimedOut:
      throw std::runtime_error(fmt_seconds(limit) + " were not enough to decode " +
                               std::to_string(size) + " bytes of Draco data (a corrupt or hostile stream)");
    case io::ChildOutcome::Status::kCrashed: break;
  }
  throw std::runtime_error("the Draco decoder " + outcome.bytes);
}

// Decodes one primitive; throws std::runtime_error with the reason.
void decode_primitive(tinygltf::Model& model, tinygltf::Primitive& prim, const tinygltf::Value& ext) {
  if (!ext.IsObject() || !ext.Get("bufferView").IsInt() || !ext.Get("attributes").IsObject())
    throw std::runtime_error("the extension needs an integer bufferView and an attributes object");
  const int view_index = ext.Get("bufferView").Get<int>();
  if (view_index < 0 || static_cast<std::size_t>(view_index) >= model.bufferViews.size())
    throw std::runtime_error("bufferView " + std::to_string(view_index) + " does not exist");
  const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(view_index)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size())
    throw std::runtime_error("bufferView " + std::to_string(view_index) + " names no buffer");
  const std::vector<unsigned char>& data = model.buffers[static_cast<std::size_t>(view.buffer)].data;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
    throw std::runtime_error("bufferView " + std::to_string(view_index) + " leaves its buffer");
  if (prim.indices < 0 || static_cast<std::size_t>(prim.indices) >= model.accessors.size())
    throw std::runtime_error("a Draco primitive needs an indices accessor");

  DecodedPrimitive d = decode_with_deadline(model, prim, ext, data.data() + view.byteOffset, view.byteLength);
  // All decoded: only now change the model (a failure above leaves the fallback data intact).
  for (const auto& [accessor, values] : d.attributes)
    if (accessor < 0 || static_cast<std::size_t>(accessor) >= model.accessors.size())
      throw std::runtime_error("the Draco decoder's answer names accessor " + std::to_string(accessor));
  const std::size_t index_count = d.indices.size() / 4;
  tinygltf::Accessor& idx = model.accessors[static_cast<std::size_t>(prim.indices)];
  idx.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  point_at(idx, add_buffer(model, std::move(d.indices)), index_count);
  for (auto& [accessor, values] : d.attributes)
    point_at(model.accessors[static_cast<std::size_t>(accessor)], add_buffer(model, std::move(values)),
             d.points);
}

}  // namespace

bool read_gltf(tinygltf::TinyGLTF& parser, tinygltf::Model& model, std::string& err,
               std::string& warn, const std::string& path, bool binary) {
  const auto plain = [&] {
    return binary ? parser.LoadBinaryFromFile(&model, &err, &warn, path)
                  : parser.LoadASCIIFromFile(&model, &err, &warn, path);
  };
  const std::string bytes = slurp(path);
  std::string text;
  std::string bin_chunks;  // .glb: every chunk after the JSON one, headers included
  if (binary) {
    if (bytes.size() < 20 || u32(bytes, 12) > bytes.size() - 20) return plain();
    text = bytes.substr(20, u32(bytes, 12));
    std::size_t end = 20 + u32(bytes, 12);
    bin_chunks = bytes.substr(std::min(end, bytes.size()));
  } else {
    text = bytes;
  }
  json j = json::parse(text, nullptr, false);
  if (!j.is_object() || !uses_draco(j)) return plain();
  patch_indices(j);
  std::string patched = j.dump();
  if (!binary)
    return parser.LoadASCIIFromString(&model, &err, &warn, patched.data(),
                                      static_cast<unsigned int>(patched.size()), base_dir(path));
  while (patched.size() % 4) patched.push_back(' ');
  std::string glb = bytes.substr(0, 8);
  put_u32(glb, static_cast<std::uint32_t>(20 + patched.size() + bin_chunks.size()));
  put_u32(glb, static_cast<std::uint32_t>(patched.size()));
  glb.append("JSON");
  glb += patched;
  glb += bin_chunks;
  return parser.LoadBinaryFromMemory(&model, &err, &warn,
                                     reinterpret_cast<const unsigned char*>(glb.data()),
                                     static_cast<unsigned int>(glb.size()), base_dir(path));
}

void decode_draco(tinygltf::Model& model, const std::string& path, std::vector<std::string>& warnings) {
  const bool required = std::find(model.extensionsRequired.begin(), model.extensionsRequired.end(),
                                  kDraco) != model.extensionsRequired.end();
  for (std::size_t m = 0; m < model.meshes.size(); ++m) {
    for (std::size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
      tinygltf::Primitive& prim = model.meshes[m].primitives[p];
      const auto ext = prim.extensions.find(kDraco);
      if (ext == prim.extensions.end()) continue;
      const std::string where = "mesh " + std::to_string(m) +
                                (model.meshes[m].name.empty() ? "" : " '" + model.meshes[m].name + "'") +
                                " primitive " + std::to_string(p);
      // Uncompressed fallback data: every accessor has a buffer view of its own (the patched
      // indices accessor points at the Draco data, which is not one).
      bool fallback = !required;
      const int draco_view = ext->second.Get("bufferView").IsInt() ? ext->second.Get("bufferView").Get<int>() : -1;
      for (const auto& [name, acc] : prim.attributes)
        if (acc >= 0 && static_cast<std::size_t>(acc) < model.accessors.size() &&
            model.accessors[static_cast<std::size_t>(acc)].bufferView < 0)
          fallback = false;
      if (prim.indices >= 0 && static_cast<std::size_t>(prim.indices) < model.accessors.size()) {
        const int v = model.accessors[static_cast<std::size_t>(prim.indices)].bufferView;
        if (v < 0 || v == draco_view) fallback = false;
      }
      try {
        decode_primitive(model, prim, ext->second);
      } catch (const std::runtime_error& e) {
        if (fallback) {
          warnings.push_back(where + ": " + kDraco + " (optional) cannot be decoded, its " +
                             "uncompressed data is used: " + e.what());
          continue;
        }
        throw LoadError(path, where + ": " + kDraco +
                                  (required ? " (a required extension)" : "") + ": " + e.what());
      }
    }
  }
}

}  // namespace ddish::scene::gltf
