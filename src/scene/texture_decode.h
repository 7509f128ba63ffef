// Decoding glTF images (PNG, JPEG, ...) to RGBA8 textures, in parallel, or reading only their
// sizes when the pixels are not needed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace ddish::scene {

struct EncodedImage {
  std::string name;  // the image's name or URI, for messages
  std::vector<std::uint8_t> bytes;
};

// Reads an image's width and height from its header into `out` without decoding pixels.
// Returns an empty string on success, else why the data is not a decodable image.
std::string read_image_header(const std::uint8_t* data, std::size_t size, Texture& out);

// One Texture per image, in order. decode_pixels = false reads the headers only (width and
// height, rgba8 left empty). An image that cannot be decoded throws a LoadError naming `file`
// and the image. threads = 0: one per hardware thread.
std::vector<Texture> decode_textures(const std::vector<EncodedImage>& images, bool decode_pixels,
                                     unsigned threads, const std::string& file);

}  // namespace ddish::scene
