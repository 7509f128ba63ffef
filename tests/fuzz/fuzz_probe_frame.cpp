// libFuzzer target for the probe stream's decoder (net/probe_frame.h): any byte string is either
// rejected with a reason or decodes to a frame whose every field is in range (indices, finite
// coefficients, moment maps of updated probes only, of all of a keyframe's, moments in [0, 1],
// finite non-zero offsets of updated or deactivated probes); a decoded frame re-encodes to a
// message that decodes to the same indices, moments and offsets, and applies to a mirror of its
// grid and moment resolution, which then holds the frame's maps, or is refused there for an
// offset beyond kMaxRelocation cells. Seeds: tests/fuzz/corpus/probe_frame/ (keyframes and
// deltas in every encoding, with zstd, L1 without moments, L2 and L4 with 2x2 and 4x4 moment
// maps, deltas mapping some of their probes, relocated probes, and one version-1 frame). The
// same input is also tried as an INFO reply's grid bounds (decode_grid_bounds; seed
// grid_bounds.bin).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "fuzz_support.h"
#include "net/probe_frame.h"
#include "net/probe_mirror.h"
#include "probes/probe_grid.h"
#include "probes/probe_volume.h"

using fuzz::require;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ddish;
  // The same bytes as an INFO reply's grid bounds: accepted only as 6 finite ordered floats, which
  // make a grid and re-encode to the same bytes.
  scene::Aabb bounds;
  if (net::decode_grid_bounds({data, size}, bounds)) {
    require(size == net::kGridBoundsBytes && !bounds.empty());
    for (int c = 0; c < 3; ++c)
      require(std::isfinite(bounds.min[c]) && std::isfinite(bounds.max[c]) && std::isfinite(bounds.extent()[c]));
    require(probes::ProbeGrid(bounds, {2, 2, 2}).probe_count() == 8);
    require(net::encode_grid_bounds(bounds) == std::vector<std::uint8_t>(data, data + size));
  }
  net::DecodeLimits limits;
  limits.max_payload_bytes = std::size_t(1) << 20;  // keeps each input's memory small
  const net::DecodeResult r = net::decode_frame({data, size}, limits);
  if (!r.ok) {
    require(!r.detail.empty());
    return 0;
  }
  const net::ProbeFrame& f = r.frame;
  const std::uint32_t probes = f.header.probe_count();
  require(probes >= 1 && probes <= net::kMaxGridProbes);
  for (std::size_t k = 0; k < f.updated.size(); ++k)
    require(f.updated[k] < probes && (k == 0 || f.updated[k] > f.updated[k - 1]));
  for (std::size_t k = 0; k < f.deactivated.size(); ++k)
    require(f.deactivated[k] < probes && (k == 0 || f.deactivated[k] > f.deactivated[k - 1]));
  for (const glm::vec3& v : f.coefficients)
    require(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z));
  require(f.moments.size() == f.mapped.size() * std::size_t(f.header.moment_texels()));
  require(f.mapped.size() <= f.updated.size() && (f.header.moment_resolution > 0 || f.mapped.empty()));
  require(f.header.kind == net::FrameKind::kDelta || f.header.moment_resolution == 0 || f.mapped == f.updated);
  for (std::size_t k = 0, a = 0; k < f.mapped.size(); ++k) {
    require(k == 0 || f.mapped[k] > f.mapped[k - 1]);
    while (a < f.updated.size() && f.updated[a] < f.mapped[k]) ++a;
    require(a < f.updated.size() && f.updated[a] == f.mapped[k]);
  }
  for (const glm::vec2& m : f.moments) require(m.x >= 0.0f && m.x <= 1.0f && m.y >= 0.0f && m.y <= 1.0f);
  require(f.relocated.size() == f.offsets.size() &&
          f.relocated.size() <= f.updated.size() + f.deactivated.size());
  for (const glm::vec3& o : f.offsets)
    require(std::isfinite(o.x) && std::isfinite(o.y) && std::isfinite(o.z) && o != glm::vec3(0.0f));
  const net::DecodeResult again = net::decode_frame(net::encode_frame(f), limits);
  require(again.ok && again.frame.updated == f.updated && again.frame.deactivated == f.deactivated &&
          again.frame.mapped == f.mapped && again.frame.moments == f.moments && again.frame.relocated == f.relocated &&
          again.frame.offsets == f.offsets);
  if (probes <= 4096) {
    probes::ProbeVolume volume(
        probes::ProbeGrid(scene::Aabb{glm::vec3(0.0f), glm::vec3(1.0f)},
                          {int(f.header.counts[0]), int(f.header.counts[1]), int(f.header.counts[2])}),
        f.header.sh_order, f.header.moment_resolution);
    net::ProbeFrame frame = f;  // the range is the client's grid's (a mismatch is refused)
    if (frame.header.moment_resolution > 0) frame.header.moment_range = volume.moment_range();
    net::ProbeMirror mirror(volume, frame.header.scene_id);
    std::vector<std::uint32_t> changed;
    if (frame.header.kind == net::FrameKind::kDelta) {  // take it on top of an empty keyframe
      net::ProbeFrame base;
      base.header = frame.header;
      base.header.kind = net::FrameKind::kKeyframe;
      base.header.frame = base.header.base_frame = frame.header.base_frame;
      require(mirror.apply(base, changed) == net::ApplyOutcome::kApplied);
    }
    const glm::vec3 bound = probes::kMaxRelocation * volume.grid().spacing();
    bool beyond = false;
    for (const glm::vec3& o : frame.offsets) beyond |= glm::any(glm::greaterThan(glm::abs(o), bound));
    require(mirror.apply(frame, changed) ==
            (beyond ? net::ApplyOutcome::kBadOffset : net::ApplyOutcome::kApplied));
    if (!beyond) {
      for (std::size_t k = 0; k < frame.relocated.size(); ++k)
        require(volume.offset(frame.relocated[k]) == frame.offsets[k]);
      const std::size_t texels = std::size_t(frame.header.moment_texels());
      for (std::size_t k = 0; k < frame.mapped.size(); ++k)
        for (std::size_t t = 0; t < texels; ++t)
          require(volume.moments(frame.mapped[k])[t] == frame.moments[k * texels + t]);
    }
  }
  return 0;
}
