#include "net/view_message.h"

#include <cmath>
#include <cstring>

#include <fmt/format.h>

#include "net/byte_io.h"
#include "net/probe_frame.h"

namespace ddish::net {
namespace {

void write_matrix(ByteWriter& w, const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      std::uint32_t bits;
      std::memcpy(&bits, &m[c][r], 4);
      w.u32(bits);
    }
}

bool read_matrix(ByteReader& r, glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) {
      std::uint32_t bits;
      if (!r.u32(bits)) return false;
      std::memcpy(&m[c][row], &bits, 4);
      if (!std::isfinite(m[c][row])) return false;
    }
  return true;
}

}  // namespace

std::vector<std::uint8_t> encode_views(std::span<const scene::View> views) {
  std::vector<std::uint8_t> out;
  ByteWriter w(out);
  for (char c : kViewMagic) w.u8(std::uint8_t(c));
  w.u16(kProtocolVersion);
  w.u16(std::uint16_t(std::min(views.size(), kMaxViewsPerClient)));
  for (std::size_t i = 0; i < views.size() && i < kMaxViewsPerClient; ++i) {
    w.u32(std::uint32_t(views[i].width));
    w.u32(std::uint32_t(views[i].height));
    write_matrix(w, views[i].view);
    write_matrix(w, views[i].projection);
  }
  return out;
}

bool decode_views(std::span<const std::uint8_t> message, std::vector<scene::View>& views,
                  std::string& problem) {
  views.clear();
  if (message.size() < 8 || std::memcmp(message.data(), kViewMagic, 4) != 0) {
    problem = "not a DDVW view message";
    return false;
  }
  ByteReader r(message.subspan(4));
  std::uint16_t version = 0, count = 0;
  r.u16(version);
  r.u16(count);
  if (version != kProtocolVersion) {
    problem = fmt::format("view message version {}", version);
    return false;
  }
  if (count == 0 || count > kMaxViewsPerClient || r.remaining() != count * kViewBytes) {
    problem = fmt::format("{} views in {} bytes", count, message.size());
    return false;
  }
  for (std::uint16_t i = 0; i < count; ++i) {
    scene::View v;
    std::uint32_t w = 0, h = 0;
    r.u32(w);
    r.u32(h);
    if (w < 1 || h < 1 || w > 16384 || h > 16384 || !read_matrix(r, v.view) ||
        !read_matrix(r, v.projection)) {
      problem = fmt::format("view {}: bad size or a non-finite matrix", i);
      views.clear();
      return false;
    }
    v.width = int(w);
    v.height = int(h);
    v.name = fmt::format("client view {}", i);
    views.push_back(std::move(v));
  }
  return true;
}

}  // namespace ddish::net
