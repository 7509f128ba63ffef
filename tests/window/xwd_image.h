// Reads the screenshot `xwd -root` writes (X Window Dump, version 7): the header's 25 big-endian
// CARD32 fields, the window name, the colour map, then ZPixmap rows of 32-bit pixels in the
// header's byte order, decoded through its channel masks to R, G, B bytes.
#pragma once

#include <cstdint>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

namespace window_test {

struct Rgb8Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // 3 bytes a pixel, row 0 at the top
  const std::uint8_t* at(int x, int y) const { return &rgb[3 * (std::size_t(y) * std::size_t(width) + std::size_t(x))]; }
};

inline Rgb8Image read_xwd(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string b{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  auto be32 = [&](std::size_t at) {
    if (at + 4 > b.size()) throw std::runtime_error(path + ": truncated XWD file");
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(b[at + i]);
    return v;
  };
  const std::uint32_t header = be32(0), version = be32(4), format = be32(8);
  const std::uint32_t width = be32(16), height = be32(20), byte_order = be32(28);
  const std::uint32_t bpp = be32(44), stride = be32(48);
  const std::uint32_t masks[3] = {be32(56), be32(60), be32(64)};
  const std::uint32_t ncolors = be32(76);
  if (version != 7 || format != 2 || bpp != 32)
    throw std::runtime_error(path + ": not a 32-bit ZPixmap XWD file");
  const std::size_t data = header + std::size_t(ncolors) * 12;
  if (data + std::size_t(stride) * height > b.size()) throw std::runtime_error(path + ": truncated pixels");
  Rgb8Image img;
  img.width = int(width);
  img.height = int(height);
  img.rgb.resize(3 * std::size_t(width) * height);
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x) {
      const std::size_t at = data + std::size_t(y) * stride + 4 * std::size_t(x);
      std::uint32_t v = 0;
      for (std::size_t i = 0; i < 4; ++i) {
        const auto byte = std::uint32_t(static_cast<unsigned char>(b[at + i]));
        v |= byte_order == 0 ? byte << (8 * i) : byte << (8 * (3 - i));  // 0: LSBFirst
      }
      for (int c = 0; c < 3; ++c) {
        const std::uint32_t m = masks[c];
        int shift = 0;
        while (m && !((m >> shift) & 1u)) ++shift;
        img.rgb[3 * (std::size_t(y) * width + x) + std::size_t(c)] = std::uint8_t((v & m) >> shift);
      }
    }
  return img;
}

}  // namespace window_test
