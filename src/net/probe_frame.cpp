#include "net/probe_frame.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include <fmt/format.h>
#include <glm/glm.hpp>
#include <zstd.h>

#include "net/byte_io.h"

namespace ddish::net {
namespace {

int coefficients_of(int order) { return (order + 1) * (order + 1); }

void write_indices(ByteWriter& w, std::span<const std::uint32_t> indices) {
  std::uint32_t next = 0;  // the smallest index the next one may have
  for (std::uint32_t i : indices) {
    w.varint(i - next);
    next = i + 1;
  }
}

DecodeResult reject(RejectKind kind, std::string detail) {
  DecodeResult r;
  r.reject = kind;
  r.detail = std::move(detail);
  return r;
}

// Reads `count` gap-coded indices below probe_count; the reject kind on failure.
bool read_indices(ByteReader& r, std::uint32_t count, std::uint32_t probe_count,
                  std::vector<std::uint32_t>& out, DecodeResult& failure) {
  out.resize(count);
  std::uint64_t next = 0;
  for (std::uint32_t k = 0; k < count; ++k) {
    std::uint32_t gap;
    if (!r.varint(gap)) {
      failure = reject(RejectKind::kSizeMismatch, "the index list runs past its payload");
      return false;
    }
    const std::uint64_t index = next + gap;
    if (index >= probe_count) {
      failure = reject(RejectKind::kBadIndex,
                       fmt::format("probe index {} outside the grid of {} probes", index, probe_count));
      return false;
    }
    out[k] = std::uint32_t(index);
    next = index + 1;
  }
  return true;
}

}  // namespace

std::string reject_name(RejectKind kind) {
  switch (kind) {
    case RejectKind::kTruncated: return "truncated";
    case RejectKind::kBadMagic: return "bad-magic";
    case RejectKind::kBadVersion: return "bad-version";
    case RejectKind::kBadHeader: return "bad-header";
    case RejectKind::kSizeMismatch: return "size-mismatch";
    case RejectKind::kBadIndex: return "bad-index";
    case RejectKind::kBadCoefficients: return "bad-coefficients";
    case RejectKind::kDecompression: return "decompression";
    case RejectKind::kSceneMismatch: return "scene-mismatch";
    case RejectKind::kBadVisibility: return "bad-visibility";
  }
  return "unknown";
}

std::size_t coefficient_bytes(const FrameHeader& h) {
  return std::size_t(probe_bytes(h.encoding, h.sh_order));
}

std::size_t map_bytes(const FrameHeader& h) { return moment_bytes(h.moment_texels()); }

std::vector<std::uint8_t> encode_frame(const FrameHeader& h, const FrameParts& parts, int zstd_level) {
  const std::size_t sh_bytes = coefficient_bytes(h);
  const std::size_t per_map = map_bytes(h);
  if (parts.coefficients.size() != parts.updated.size() * sh_bytes ||
      parts.maps.size() != parts.mapped.size() * per_map || parts.mapped.size() > parts.updated.size() ||
      (per_map == 0 && !parts.mapped.empty()) ||
      parts.deactivated.size() != parts.deactivated_flags.size() ||
      parts.relocated.size() != parts.offsets.size() || parts.relocated.size() > parts.updated.size() + parts.deactivated.size())
    throw std::invalid_argument("encode_frame: probe data does not match the index lists");
  std::vector<std::uint8_t> payload;
  payload.reserve(parts.updated.size() * (sh_bytes + 1) + parts.mapped.size() * (per_map + 1) +
                  parts.deactivated.size() * 2 + parts.relocated.size() * 13);
  ByteWriter p(payload);
  write_indices(p, parts.updated);
  write_indices(p, parts.deactivated);
  write_indices(p, parts.relocated);
  write_indices(p, parts.mapped);
  p.bytes(parts.deactivated_flags);
  p.bytes(parts.coefficients);
  p.bytes(parts.maps);
  for (const glm::vec3& o : parts.offsets)
    for (int a = 0; a < 3; ++a) p.f32(o[a]);
  const std::uint32_t raw_bytes = std::uint32_t(payload.size());
  if (h.zstd) {
    std::vector<std::uint8_t> packed(ZSTD_compressBound(payload.size()));
    const std::size_t n =
        ZSTD_compress(packed.data(), packed.size(), payload.data(), payload.size(), zstd_level);
    if (ZSTD_isError(n)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(n));
    packed.resize(n);
    payload = std::move(packed);
  }
  std::vector<std::uint8_t> out;
  out.reserve(kFrameHeaderBytes + payload.size());
  ByteWriter w(out);
  for (char c : kFrameMagic) w.u8(std::uint8_t(c));
  w.u16(kProtocolVersion);
  w.u8(std::uint8_t(h.kind));
  w.u8(std::uint8_t(h.encoding));
  w.u8(std::uint8_t(h.sh_order));
  w.u8(h.zstd ? kFrameFlagZstd : 0);
  w.u8(std::uint8_t(h.moment_resolution));
  w.u8(0);
  for (std::uint32_t c : h.counts) w.u32(c);
  w.u64(h.scene_id);
  w.u64(h.stream_id);
  w.u64(h.frame);
  w.u64(h.base_frame);
  w.i64(h.server_time_us);
  w.f64(h.scene_time);
  w.f32(h.moment_resolution > 0 ? h.moment_range : 0.0f);
  w.u32(std::uint32_t(parts.updated.size()));
  w.u32(std::uint32_t(parts.deactivated.size()));
  w.u32(std::uint32_t(parts.relocated.size()));
  w.u32(std::uint32_t(parts.mapped.size()));
  w.u32(std::uint32_t(payload.size()));
  w.u32(raw_bytes);
  w.bytes(payload);
  return out;
}

std::vector<std::uint8_t> encode_frame(const ProbeFrame& f, std::uint32_t* saturated,
                                       int zstd_level) {
  const int n = coefficients_of(f.header.sh_order);
  const std::size_t texels = std::size_t(f.header.moment_texels());
  const std::size_t sh_bytes = coefficient_bytes(f.header);
  const std::size_t per_map = map_bytes(f.header);
  if (f.coefficients.size() != f.updated.size() * std::size_t(n) ||
      f.moments.size() != f.mapped.size() * texels)
    throw std::invalid_argument("encode_frame: coefficients or moments do not match the probe lists");
  std::vector<std::uint8_t> coefficients(f.updated.size() * sh_bytes), maps(f.mapped.size() * per_map);
  std::vector<std::uint8_t> inexact(f.updated.size(), 0);
  for (std::size_t k = 0; k < f.updated.size(); ++k)
    inexact[k] = !encode_probe(f.header.encoding, f.header.sh_order,
                               std::span(f.coefficients).subspan(k * std::size_t(n), std::size_t(n)),
                               std::span(coefficients).subspan(k * sh_bytes, sh_bytes));
  // A map's rounding counts against its probe (mapped is a subset of updated when well formed).
  for (std::size_t m = 0, k = 0; m < f.mapped.size(); ++m) {
    const bool exact = encode_moments(std::span(f.moments).subspan(m * texels, texels),
                                      std::span(maps).subspan(m * per_map, per_map));
    while (k < f.updated.size() && f.updated[k] < f.mapped[m]) ++k;
    if (!exact && k < f.updated.size()) inexact[k] = 1;
  }
  if (saturated) *saturated = std::uint32_t(std::count(inexact.begin(), inexact.end(), std::uint8_t(1)));
  return encode_frame(f.header,
                      FrameParts{f.updated, coefficients, f.mapped, maps, f.deactivated, f.deactivated_flags,
                                 f.relocated, f.offsets},
                      zstd_level);
}

// The header after its version: kind .. moment range, in their wire order (shared by the
// header-only peek and the full decoder). The raw kind, encoding, order, flags and reserved
// byte are returned for the decoder's checks.
struct RawHeader {
  std::uint8_t kind = 0, encoding = 0, order = 0, flags = 0, moments = 0, reserved = 0;
};
static RawHeader read_header_fields(ByteReader& r, FrameHeader& h) {
  RawHeader raw;
  r.u8(raw.kind);
  r.u8(raw.encoding);
  r.u8(raw.order);
  r.u8(raw.flags);
  r.u8(raw.moments);
  r.u8(raw.reserved);
  for (std::uint32_t& c : h.counts) r.u32(c);
  r.u64(h.scene_id);
  r.u64(h.stream_id);
  r.u64(h.frame);
  r.u64(h.base_frame);
  r.i64(h.server_time_us);
  r.f64(h.scene_time);
  r.f32(h.moment_range);
  h.kind = FrameKind(raw.kind);
  h.encoding = Encoding(raw.encoding);
  h.sh_order = raw.order;
  h.zstd = (raw.flags & kFrameFlagZstd) != 0;
  h.moment_resolution = raw.moments;
  return raw;
}

bool peek_header(std::span<const std::uint8_t> message, FrameHeader& h) {
  if (message.size() < kFrameHeaderBytes || std::memcmp(message.data(), kFrameMagic, 4) != 0)
    return false;
  ByteReader r(message.subspan(4));
  std::uint16_t version;
  r.u16(version);
  if (version != kProtocolVersion) return false;
  read_header_fields(r, h);
  return true;
}

DecodeResult decode_frame(std::span<const std::uint8_t> message, const DecodeLimits& limits) {
  // Magic and version first: a peer of another version gets "bad-version" whatever its header's
  // size (version 1's was 88 bytes).
  if (message.size() >= 4 && std::memcmp(message.data(), kFrameMagic, 4) != 0)
    return reject(RejectKind::kBadMagic, "not a DDPF probe frame");
  if (message.size() >= 6) {
    const std::uint16_t version = std::uint16_t(message[4] | (message[5] << 8));
    if (version != kProtocolVersion)
      return reject(RejectKind::kBadVersion,
                    fmt::format("protocol version {}, this build speaks {}", version, kProtocolVersion));
  }
  if (message.size() < kFrameHeaderBytes)
    return reject(RejectKind::kTruncated,
                  fmt::format("{} bytes, shorter than the {}-byte header", message.size(), kFrameHeaderBytes));
  ByteReader r(message.subspan(6, kFrameHeaderBytes - 6));
  std::uint32_t updated = 0, deactivated = 0, relocated = 0, mapped = 0, payload_bytes = 0, raw_bytes = 0;
  FrameHeader h;
  const RawHeader raw = read_header_fields(r, h);
  r.u32(updated);
  r.u32(deactivated);
  r.u32(relocated);
  r.u32(mapped);
  r.u32(payload_bytes);
  r.u32(raw_bytes);
  if (raw.kind > 1) return reject(RejectKind::kBadHeader, fmt::format("unknown frame kind {}", raw.kind));
  if (raw.encoding >= kEncodingCount)
    return reject(RejectKind::kBadHeader, fmt::format("unknown encoding {}", raw.encoding));
  if (raw.order < 1 || raw.order > 4)
    return reject(RejectKind::kBadHeader, fmt::format("SH order {} outside 1..4", raw.order));
  if ((raw.flags & ~kFrameFlagZstd) != 0 || raw.reserved != 0)
    return reject(RejectKind::kBadHeader, "reserved flag bits set");
  if (raw.moments > kMaxWireMomentResolution)
    return reject(RejectKind::kBadHeader, fmt::format("moment resolution {} outside 0..{}", raw.moments,
                                                      kMaxWireMomentResolution));
  if (raw.moments > 0 ? !(std::isfinite(h.moment_range) && h.moment_range > 0.0f)
                      : std::bit_cast<std::uint32_t>(h.moment_range) != 0)
    return reject(RejectKind::kBadHeader,
                  fmt::format("moment range {} for moment resolution {}", h.moment_range, raw.moments));
  const std::uint64_t probes = std::uint64_t(h.counts[0]) * h.counts[1] * h.counts[2];
  if (probes == 0 || probes > kMaxGridProbes)
    return reject(RejectKind::kBadHeader,
                  fmt::format("grid {}x{}x{} outside 1..{} probes", h.counts[0], h.counts[1],
                              h.counts[2], kMaxGridProbes));
  if (!std::isfinite(h.scene_time))
    return reject(RejectKind::kBadHeader, "scene time is not finite");
  if (h.kind == FrameKind::kKeyframe ? h.base_frame != h.frame : h.base_frame >= h.frame)
    return reject(RejectKind::kBadHeader,
                  fmt::format("base frame {} of frame {} is not what a {} has", h.base_frame, h.frame,
                              h.kind == FrameKind::kKeyframe ? "keyframe" : "delta"));
  if (std::uint64_t(updated) + deactivated > probes)
    return reject(RejectKind::kSizeMismatch,
                  fmt::format("{} updated + {} deactivated probes in a grid of {}", updated,
                              deactivated, probes));
  if (relocated > std::uint64_t(updated) + deactivated)
    return reject(RejectKind::kSizeMismatch,
                  fmt::format("{} relocated probes among {} updated and {} deactivated", relocated,
                              updated, deactivated));
  if (raw.moments == 0 ? mapped != 0 : mapped > updated)
    return reject(RejectKind::kSizeMismatch,
                  fmt::format("{} moment maps for {} updated probes at moment resolution {}", mapped,
                              updated, raw.moments));
  if (h.kind == FrameKind::kKeyframe && raw.moments > 0 && mapped != updated)
    return reject(RejectKind::kBadVisibility,
                  fmt::format("a keyframe with {} moment maps for its {} probes", mapped, updated));
  const std::size_t body = message.size() - kFrameHeaderBytes;
  if (body < payload_bytes)
    return reject(RejectKind::kTruncated,
                  fmt::format("payload of {} bytes announced, {} present", payload_bytes, body));
  if (body > payload_bytes)
    return reject(RejectKind::kSizeMismatch,
                  fmt::format("{} bytes after a payload of {}", body - payload_bytes, payload_bytes));
  // The uncompressed size is bounded by the counts: 1..5 bytes per index, one flag byte per
  // deactivated probe, coefficients per updated probe, a map per mapped one, 12 offset bytes
  // per relocated one.
  const std::size_t sh_bytes = coefficient_bytes(h);
  const std::size_t per_map = map_bytes(h);
  const std::uint64_t fixed = std::uint64_t(deactivated) + std::uint64_t(updated) * sh_bytes +
                              std::uint64_t(mapped) * per_map + std::uint64_t(relocated) * 12;
  const std::uint64_t indices = std::uint64_t(updated) + deactivated + relocated + mapped;
  if (raw_bytes < fixed + indices || raw_bytes > fixed + 5 * indices)
    return reject(RejectKind::kSizeMismatch,
                  fmt::format("payload of {} bytes for {} updated, {} deactivated, {} relocated and {} mapped probes",
                              raw_bytes, updated, deactivated, relocated, mapped));
  if (raw_bytes > limits.max_payload_bytes)
    return reject(RejectKind::kSizeMismatch,
                  fmt::format("payload of {} bytes beyond the limit of {}", raw_bytes,
                              limits.max_payload_bytes));
  if (!h.zstd && raw_bytes != payload_bytes)
    return reject(RejectKind::kSizeMismatch, "uncompressed payload sizes differ");
  std::span<const std::uint8_t> payload = message.subspan(kFrameHeaderBytes);
  std::vector<std::uint8_t> inflated;
  if (h.zstd) {
    const unsigned long long content = ZSTD_getFrameContentSize(payload.data(), payload.size());
    if (content == ZSTD_CONTENTSIZE_ERROR || content == ZSTD_CONTENTSIZE_UNKNOWN || content != raw_bytes)
      return reject(RejectKind::kDecompression, "zstd frame size missing or unlike the header's");
    inflated.resize(raw_bytes);
    const std::size_t n = ZSTD_decompress(inflated.data(), inflated.size(), payload.data(), payload.size());
    if (ZSTD_isError(n)) return reject(RejectKind::kDecompression, std::string("zstd: ") + ZSTD_getErrorName(n));
    if (n != raw_bytes) return reject(RejectKind::kDecompression, "zstd output shorter than announced");
    payload = inflated;
  }
  DecodeResult result;
  ProbeFrame& f = result.frame;
  f.header = h;
  ByteReader p(payload);
  DecodeResult failure;
  if (!read_indices(p, updated, std::uint32_t(probes), f.updated, failure) ||
      !read_indices(p, deactivated, std::uint32_t(probes), f.deactivated, failure) ||
      !read_indices(p, relocated, std::uint32_t(probes), f.relocated, failure) ||
      !read_indices(p, mapped, std::uint32_t(probes), f.mapped, failure))
    return failure;
  // Disjoint: a probe is either updated or deactivated.
  for (std::size_t a = 0, b = 0; a < f.updated.size() && b < f.deactivated.size();) {
    if (f.updated[a] == f.deactivated[b])
      return reject(RejectKind::kBadIndex,
                    fmt::format("probe {} both updated and deactivated", f.updated[a]));
    f.updated[a] < f.deactivated[b] ? ++a : ++b;
  }
  // Relocated probes are updated or deactivated ones (an offset travels with the probe's news).
  for (std::size_t a = 0, d = 0, b = 0; b < f.relocated.size();) {
    const std::uint32_t want = f.relocated[b];
    while (a < f.updated.size() && f.updated[a] < want) ++a;
    while (d < f.deactivated.size() && f.deactivated[d] < want) ++d;
    if (!(a < f.updated.size() && f.updated[a] == want) && !(d < f.deactivated.size() && f.deactivated[d] == want))
      return reject(RejectKind::kBadVisibility,
                    fmt::format("probe {} has an offset but is neither updated nor deactivated", want));
    ++b;
  }
  // Mapped probes are updated ones (a map travels with its probe's coefficients).
  for (std::size_t a = 0, b = 0; b < f.mapped.size(); ++b) {
    while (a < f.updated.size() && f.updated[a] < f.mapped[b]) ++a;
    if (a == f.updated.size() || f.updated[a] != f.mapped[b])
      return reject(RejectKind::kBadVisibility,
                    fmt::format("probe {} has a moment map but is not updated", f.mapped[b]));
  }
  std::span<const std::uint8_t> flag_bytes, coefficient_bytes_in, map_bytes_in;
  if (!p.bytes(deactivated, flag_bytes))
    return reject(RejectKind::kSizeMismatch, "payload ends inside the deactivated probes' flags");
  for (std::uint8_t fl : flag_bytes)
    if ((fl & kWireFlagInactive) == 0 || (fl & ~(kWireFlagInactive | kWireFlagInsideGeometry)) != 0)
      return reject(RejectKind::kBadCoefficients,
                    fmt::format("deactivated probe flags {:#04x}", fl));
  f.deactivated_flags.assign(flag_bytes.begin(), flag_bytes.end());
  if (p.remaining() != std::size_t(updated) * sh_bytes + std::size_t(mapped) * per_map + std::size_t(relocated) * 12)
    return reject(RejectKind::kSizeMismatch,
                  fmt::format("{} bytes for {} probes' coefficients of {} bytes, {} maps of {} and {} offsets",
                              p.remaining(), updated, sh_bytes, mapped, per_map, relocated));
  p.bytes(std::size_t(updated) * sh_bytes, coefficient_bytes_in);
  p.bytes(std::size_t(mapped) * per_map, map_bytes_in);
  const std::size_t n = std::size_t(coefficients_of(h.sh_order));
  const std::size_t texels = std::size_t(h.moment_texels());
  f.coefficients.resize(std::size_t(updated) * n);
  f.moments.resize(std::size_t(mapped) * texels);
  for (std::size_t k = 0; k < updated; ++k)
    if (!decode_probe(h.encoding, h.sh_order, coefficient_bytes_in.subspan(k * sh_bytes, sh_bytes),
                      std::span(f.coefficients).subspan(k * n, n)))
      return reject(RejectKind::kBadCoefficients,
                    fmt::format("probe {}: not a valid {} code", f.updated[k], encoding_name(h.encoding)));
  for (std::size_t k = 0; k < mapped; ++k) {
    std::size_t texel = 0;
    if (!decode_moments(map_bytes_in.subspan(k * per_map, per_map),
                        std::span(f.moments).subspan(k * texels, texels), &texel))
      return reject(RejectKind::kBadVisibility,
                    fmt::format("probe {}: moment texel {} is not a number in [0, 1]", f.mapped[k], texel));
  }
  f.offsets.resize(relocated);
  for (std::size_t k = 0; k < relocated; ++k) {
    glm::vec3& o = f.offsets[k];
    for (int a = 0; a < 3; ++a) p.f32(o[a]);
    if (!std::isfinite(o.x) || !std::isfinite(o.y) || !std::isfinite(o.z) || o == glm::vec3(0.0f))
      return reject(RejectKind::kBadVisibility,
                    fmt::format("probe {}: offset ({}, {}, {}) is not finite and non-zero", f.relocated[k],
                                o.x, o.y, o.z));
  }
  result.ok = true;
  return result;
}

std::vector<std::uint8_t> encode_grid_bounds(const scene::Aabb& bounds) {
  std::vector<std::uint8_t> out;
  ByteWriter w(out);
  for (const glm::vec3& corner : {bounds.min, bounds.max})
    for (int c = 0; c < 3; ++c) w.f32(corner[c]);
  return out;
}

bool decode_grid_bounds(std::span<const std::uint8_t> bytes, scene::Aabb& bounds) {
  if (bytes.size() != kGridBoundsBytes) return false;
  ByteReader r(bytes);
  scene::Aabb b;
  for (glm::vec3* corner : {&b.min, &b.max})
    for (int c = 0; c < 3; ++c)
      if (!r.f32((*corner)[c]) || !std::isfinite((*corner)[c])) return false;
  if (b.empty()) return false;
  for (int c = 0; c < 3; ++c)
    if (!std::isfinite(b.max[c] - b.min[c])) return false;  // a grid's spacing must be finite too
  bounds = b;
  return true;
}

}  // namespace ddish::net
