// A scene too large for this machine is refused before the work that would exhaust memory
// (reading the file, decoding its textures), with one line that says what it needs and what is
// free, instead of the kernel's out-of-memory killer ending the process half-way.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace ddish::scene {

// What holding the scene's textures costs: the decoded RGBA8 pixels of every image, plus the
// decoder's working copy of the largest one (stb_image decodes to its own buffer first).
// A lower bound of what loading needs; the GPU upload and the mip chain come later.
std::uint64_t texture_decode_bytes(const std::vector<Texture>& headers);

// Throws LoadError naming `file` when reading a file of `file_bytes` cannot fit in `available`
// bytes: tinygltf holds the whole file and then a copy of its buffers, so twice its size.
void check_file_fits(const std::string& file, std::uint64_t file_bytes, std::uint64_t available);

// Throws LoadError naming `file` when decoding the images of `headers` (sizes only) cannot fit
// in `available` bytes.
void check_textures_fit(const std::string& file, const std::vector<Texture>& headers,
                        std::uint64_t available);

}  // namespace ddish::scene
