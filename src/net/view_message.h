// The upstream message a client sends its server: the views it renders this frame, so that the
// server's scheduler ranks probes by the union of every client's views. Little-endian:
//   0  4 magic "DDVW"
//   4  2 u16 protocol version (kProtocolVersion)
//   6  2 u16 view count, 1..kMaxViewsPerClient
//   8  -  per view: u32 width, u32 height (1..16384), f32 × 16 world-to-camera matrix,
//         f32 × 16 projection (column-major, scene/view.h): 136 bytes
// Nothing after. The decoder refuses a wrong size, count, image size or a non-finite matrix.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "scene/view.h"

namespace ddish::net {

inline constexpr char kViewMagic[4] = {'D', 'D', 'V', 'W'};
inline constexpr std::size_t kMaxViewsPerClient = 256;
inline constexpr std::size_t kViewBytes = 8 + 2 * 64;

std::vector<std::uint8_t> encode_views(std::span<const scene::View> views);

// The views of a message; false (with `problem` set) for anything malformed.
bool decode_views(std::span<const std::uint8_t> message, std::vector<scene::View>& views,
                  std::string& problem);

}  // namespace ddish::net
