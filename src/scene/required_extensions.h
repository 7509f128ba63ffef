// The extensions a glTF file (.gltf or .glb) lists as required, read from its JSON alone. The
// loader asks when tinygltf has refused a file: a required extension that changes how buffers
// are laid out (KHR_draco_mesh_compression, EXT_meshopt_compression) makes tinygltf fail with an
// accessor error, and the extension is the clear reason to give instead.
#pragma once

#include <string>
#include <vector>

namespace ddish::scene {

// extensionsRequired of the file; empty when it has none or its JSON cannot be read.
std::vector<std::string> required_extensions(const std::string& path);

}  // namespace ddish::scene
