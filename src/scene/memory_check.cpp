#include "scene/memory_check.h"

#include <algorithm>

#include "io/host_memory.h"
#include "scene/load_error.h"

namespace ddish::scene {

std::uint64_t texture_decode_bytes(const std::vector<Texture>& headers) {
  std::uint64_t total = 0, largest = 0;
  for (const Texture& t : headers) {
    const std::uint64_t bytes = std::uint64_t(std::max(t.width, 0)) * std::uint64_t(std::max(t.height, 0)) * 4;
    total += bytes;
    largest = std::max(largest, bytes);
  }
  return total + largest;
}

void check_file_fits(const std::string& file, std::uint64_t file_bytes, std::uint64_t available) {
  const std::uint64_t need = file_bytes > UINT64_MAX / 2 ? UINT64_MAX : file_bytes * 2;
  if (need > available)
    throw LoadError(file, "the file is " + io::format_bytes(file_bytes) + " and reading it needs " +
                              io::format_bytes(need) + " of memory, more than the " +
                              io::format_bytes(available) + " available");
}

void check_textures_fit(const std::string& file, const std::vector<Texture>& headers,
                        std::uint64_t available) {
  const std::uint64_t need = texture_decode_bytes(headers);
  if (need <= available) return;
  const auto largest = std::max_element(headers.begin(), headers.end(), [](const Texture& a, const Texture& b) {
    return std::uint64_t(a.width) * std::uint64_t(a.height) < std::uint64_t(b.width) * std::uint64_t(b.height);
  });
  throw LoadError(file, "its " + std::to_string(headers.size()) + " image" + (headers.size() == 1 ? "" : "s") +
                            " decode to " + io::format_bytes(need) + " (the largest is " +
                            std::to_string(largest->width) + "x" + std::to_string(largest->height) +
                            "), more than the " + io::format_bytes(available) +
                            " of memory available: smaller textures, or a machine with more memory");
}

}  // namespace ddish::scene
