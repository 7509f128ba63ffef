#include "scene/required_extensions.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>

#include <nlohmann/json.hpp>

namespace ddish::scene {

namespace {

// The JSON text of a .gltf file, or of a .glb's first chunk (12-byte header, then the chunk's
// length and type "JSON"); empty when the file is neither.
std::string json_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0) return bytes;
  std::uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, 4);
  if (bytes.compare(16, 4, "JSON") != 0 || length > bytes.size() - 20) return {};
  return bytes.substr(20, length);
}

}  // namespace

std::vector<std::string> required_extensions(const std::string& path) {
  const nlohmann::json j = nlohmann::json::parse(json_text(path), nullptr, false);
  std::vector<std::string> out;
  if (!j.is_object() || !j.contains("extensionsRequired") || !j["extensionsRequired"].is_array())
    return out;
  for (const nlohmann::json& e : j["extensionsRequired"])
    if (e.is_string()) out.push_back(e.get<std::string>());
  return out;
}

}  // namespace ddish::scene
