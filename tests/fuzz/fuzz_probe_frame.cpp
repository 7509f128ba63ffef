// libFuzzer target for the probe stream's decoder (net/probe_frame.h): any byte string is either
// rejected with a reason or decodes to a frame whose every field is in range; a decoded frame
// re-encodes to a message that decodes to the same indices, and applies to a mirror of its grid.
// Seeds: tests/fuzz/corpus/probe_frame/ (keyframes and deltas in every encoding, with zstd).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fuzz_support.h"
#include "net/probe_frame.h"
#include "net/probe_mirror.h"
#include "probes/probe_volume.h"

using fuzz::require;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ddish;
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
  const net::DecodeResult again = net::decode_frame(net::encode_frame(f), limits);
  require(again.ok && again.frame.updated == f.updated && again.frame.deactivated == f.deactivated);
  if (probes <= 4096) {
    probes::ProbeVolume volume(
        probes::ProbeGrid(scene::Aabb{glm::vec3(0.0f), glm::vec3(1.0f)},
                          {int(f.header.counts[0]), int(f.header.counts[1]), int(f.header.counts[2])}),
        f.header.sh_order);
    net::ProbeMirror mirror(volume, f.header.scene_id);
    std::vector<std::uint32_t> changed;
    if (f.header.kind == net::FrameKind::kDelta) {  // take it on top of an empty keyframe
      net::ProbeFrame base;
      base.header = f.header;
      base.header.kind = net::FrameKind::kKeyframe;
      base.header.frame = base.header.base_frame = f.header.base_frame;
      require(mirror.apply(base, changed) == net::ApplyOutcome::kApplied);
    }
    require(mirror.apply(f, changed) == net::ApplyOutcome::kApplied);
  }
  return 0;
}
