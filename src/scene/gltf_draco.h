// KHR_draco_mesh_compression, decoded with Google's Draco library (Debian libdraco-dev).
// tinygltf (Debian's build has no Draco) refuses a Draco primitive's indices accessor, which has
// no buffer view of its own. So the loader hands tinygltf the file's JSON with each such
// accessor pointed at its primitive's Draco buffer view (read_gltf below), and once the buffers
// are loaded decodes every Draco primitive into new buffers that its indices and attribute
// accessors then read (decode_draco), through the same checked accessor code as any file.
// libdraco trusts counts in the stream (a 1.3 KB file can keep it busy for seconds), so each
// primitive is decoded in a child process with a deadline (io/child_process.h): a stream that
// takes longer than 2 s + 10 s per MiB of compressed data is a LoadError, not a hang.
#pragma once

#include <string>
#include <vector>

#include <tiny_gltf.h>

namespace ddish::scene::gltf {

// tinygltf's load of `path` (.gltf or .glb); a file whose JSON uses KHR_draco_mesh_compression
// is loaded from memory with its Draco accessors patched as above. False with err like tinygltf.
bool read_gltf(tinygltf::TinyGLTF& parser, tinygltf::Model& model, std::string& err,
               std::string& warn, const std::string& path, bool binary);

// Decodes every Draco primitive of the model into new buffers and buffer views. A primitive
// that cannot be decoded is a LoadError naming it (and whether the extension is required); when
// the extension is optional and the primitive's accessors carry their own uncompressed data, a
// warning is added instead and that data is used.
void decode_draco(tinygltf::Model& model, const std::string& path, std::vector<std::string>& warnings);

}  // namespace ddish::scene::gltf
