#include "scene/texture_decode.h"

#include <algorithm>
#include <atomic>
#include <climits>
#include <cstring>
#include <thread>

#include <stb_image.h>

#include "scene/load_error.h"

namespace ddish::scene {

std::string read_image_header(const std::uint8_t* bytes, std::size_t size, Texture& out) {
  if (size == 0) return "no image data";
  if (size > std::size_t(INT_MAX)) return "image data larger than 2 GiB";
  int w = 0, h = 0, comp = 0;
  if (!stbi_info_from_memory(bytes, int(size), &w, &h, &comp)) {
    const char* why = stbi_failure_reason();
    return std::string("not a decodable image (") + (why ? why : "unknown format") + ")";
  }
  if (w <= 0 || h <= 0) return "image has no pixels";
  out.width = w;
  out.height = h;
  return {};
}

namespace {

// Decodes one image; returns an empty string on success, else the reason.
std::string decode_one(const EncodedImage& in, bool decode_pixels, Texture& out) {
  out.name = in.name;
  std::string header = read_image_header(in.bytes.data(), in.bytes.size(), out);
  if (!header.empty()) return header;
  if (!decode_pixels) return {};
  int w = 0, h = 0, comp = 0;
  stbi_uc* pixels = stbi_load_from_memory(in.bytes.data(), int(in.bytes.size()), &w, &h, &comp, 4);
  if (!pixels) {
    const char* why = stbi_failure_reason();
    return std::string("cannot be decoded (") + (why ? why : "corrupt data") + ")";
  }
  out.rgba8.assign(pixels, pixels + std::size_t(w) * std::size_t(h) * 4);
  stbi_image_free(pixels);
  return {};
}

}  // namespace

std::vector<Texture> decode_textures(const std::vector<EncodedImage>& images, bool decode_pixels,
                                     unsigned threads, const std::string& file) {
  std::vector<Texture> out(images.size());
  std::vector<std::string> errors(images.size());
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  // Header reads cost microseconds; threads only pay off when pixels are decoded.
  if (!decode_pixels) threads = 1;
  threads = std::min<unsigned>(threads, unsigned(std::max<std::size_t>(images.size(), 1)));
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t i = next++; i < images.size(); i = next++)
      errors[i] = decode_one(images[i], decode_pixels, out[i]);
  };
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (auto& th : pool) th.join();
  for (std::size_t i = 0; i < images.size(); ++i)
    if (!errors[i].empty())
      throw LoadError(file,
                      "image " + std::to_string(i) + " '" + images[i].name + "': " + errors[i]);
  return out;
}

}  // namespace ddish::scene
