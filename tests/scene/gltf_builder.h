// Test helper: builds small glTF files (JSON + one binary buffer) in a temporary directory, as
// .gltf with an external .bin, .gltf with a data-URI buffer, or .glb.
#pragma once

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/gltf_loader.h"
#include "scene/load_error.h"

namespace ddish::test {

enum class BufferMode { External, DataUri, Glb };

// A fresh directory under the system temp dir, removed when the object goes away.
struct TempDir {
  std::filesystem::path path;
  explicit TempDir(const std::string& tag) {
    path = std::filesystem::temp_directory_path() /
           ("ddish_" + tag + "_" + std::to_string(std::uintptr_t(this)) + "_" +
            std::to_string(std::rand()));
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  std::string file(const std::string& name) const { return (path / name).string(); }
};

// The LoadError message of loading `path`, or "(loaded)" when it loads.
inline std::string load_message(const std::string& path) {
  try {
    scene::load_scene(path);
  } catch (const scene::LoadError& e) {
    return e.what();
  }
  return "(loaded)";
}

inline void write_file(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

class GltfBuilder {
 public:
  nlohmann::json doc = {{"asset", {{"version", "2.0"}}}};
  std::vector<std::uint8_t> bin;

  // Appends raw data as a buffer view (4-byte aligned) and returns its index.
  int add_view(const void* data, std::size_t bytes, int stride = 0) {
    while (bin.size() % 4) bin.push_back(0);
    std::size_t offset = bin.size();
    bin.resize(offset + bytes);
    std::memcpy(bin.data() + offset, data, bytes);
    nlohmann::json v = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}};
    if (stride) v["byteStride"] = stride;
    doc["bufferViews"].push_back(v);
    return int(doc["bufferViews"].size()) - 1;
  }

  // A float accessor of `count` elements of `type` ("SCALAR", "VEC2", "VEC3", "VEC4").
  int add_floats(const std::vector<float>& values, const char* type, std::size_t count) {
    int view = add_view(values.data(), values.size() * sizeof(float));
    doc["accessors"].push_back(
        {{"bufferView", view}, {"componentType", 5126}, {"count", count}, {"type", type}});
    return int(doc["accessors"].size()) - 1;
  }

  int add_indices(const std::vector<std::uint32_t>& idx) {
    int view = add_view(idx.data(), idx.size() * 4);
    doc["accessors"].push_back(
        {{"bufferView", view}, {"componentType", 5125}, {"count", idx.size()}, {"type", "SCALAR"}});
    return int(doc["accessors"].size()) - 1;
  }

  // A unit quad in the XY plane facing +Z (two triangles), optionally without indices.
  int add_quad_mesh(bool indexed = true, int material = -1) {
    std::vector<float> pos = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    std::vector<float> uv = {0, 1, 1, 1, 1, 0, 0, 0};
    nlohmann::json prim;
    if (indexed) {
      prim["attributes"]["POSITION"] = add_floats(pos, "VEC3", 4);
      prim["attributes"]["TEXCOORD_0"] = add_floats(uv, "VEC2", 4);
      prim["indices"] = add_indices({0, 1, 2, 0, 2, 3});
    } else {
      std::vector<float> p6, uv6;
      for (int i : {0, 1, 2, 0, 2, 3}) {
        p6.insert(p6.end(), {pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]});
        uv6.insert(uv6.end(), {uv[2 * i], uv[2 * i + 1]});
      }
      prim["attributes"]["POSITION"] = add_floats(p6, "VEC3", 6);
      prim["attributes"]["TEXCOORD_0"] = add_floats(uv6, "VEC2", 6);
    }
    if (material >= 0) prim["material"] = material;
    doc["meshes"].push_back({{"name", "quad"}, {"primitives", {prim}}});
    return int(doc["meshes"].size()) - 1;
  }

  int add_node(nlohmann::json node) {
    doc["nodes"].push_back(std::move(node));
    return int(doc["nodes"].size()) - 1;
  }

  // Writes dir/name (+ name.bin for External) and returns the path of the glTF file.
  std::string write(const std::string& dir, const std::string& name, BufferMode mode) const {
    nlohmann::json d = doc;
    std::string path = (std::filesystem::path(dir) / name).string();
    if (!bin.empty()) {
      nlohmann::json buf = {{"byteLength", bin.size()}};
      if (mode == BufferMode::External) {
        buf["uri"] = name + ".bin";
        std::ofstream(path + ".bin", std::ios::binary)
            .write(reinterpret_cast<const char*>(bin.data()), std::streamsize(bin.size()));
      } else if (mode == BufferMode::DataUri) {
        buf["uri"] = "data:application/octet-stream;base64," + base64(bin);
      }
      d["buffers"] = {buf};
    }
    if (mode != BufferMode::Glb) {
      write_file(path, d.dump(1));
      return path;
    }
    std::string json = d.dump();
    while (json.size() % 4) json += ' ';
    std::vector<std::uint8_t> body = bin;
    while (body.size() % 4) body.push_back(0);
    std::uint32_t total =
        12 + 8 + std::uint32_t(json.size()) + (body.empty() ? 0 : 8 + std::uint32_t(body.size()));
    std::ofstream out(path, std::ios::binary);
    auto u32 = [&out](std::uint32_t v) { out.write(reinterpret_cast<const char*>(&v), 4); };
    out.write("glTF", 4);
    u32(2);
    u32(total);
    u32(std::uint32_t(json.size()));
    u32(0x4E4F534A);  // JSON
    out.write(json.data(), std::streamsize(json.size()));
    if (!body.empty()) {
      u32(std::uint32_t(body.size()));
      u32(0x004E4942);  // BIN
      out.write(reinterpret_cast<const char*>(body.data()), std::streamsize(body.size()));
    }
    return path;
  }

  static std::string base64(const std::vector<std::uint8_t>& data) {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < data.size(); i += 3) {
      std::uint32_t n = std::uint32_t(data[i]) << 16;
      if (i + 1 < data.size()) n |= std::uint32_t(data[i + 1]) << 8;
      if (i + 2 < data.size()) n |= data[i + 2];
      out += table[(n >> 18) & 63];
      out += table[(n >> 12) & 63];
      out += i + 1 < data.size() ? table[(n >> 6) & 63] : '=';
      out += i + 2 < data.size() ? table[n & 63] : '=';
    }
    return out;
  }
};

}  // namespace ddish::test
