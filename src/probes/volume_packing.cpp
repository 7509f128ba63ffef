#include "probes/volume_packing.h"

#include <stdexcept>

namespace ddish::probes {

namespace {

int severity(sh::PackStatus s) {
  switch (s) {
    case sh::PackStatus::kOk: return 0;
    case sh::PackStatus::kOverflow: return 1;
    case sh::PackStatus::kNotFinite: return 2;
    case sh::PackStatus::kBadSize: return 3;
  }
  return 3;
}

}  // namespace

PackedVolume pack_volume(const ProbeVolume& volume, EncodingPolicy policy) {
  PackedVolume out;
  out.sh_order = volume.sh_order();
  out.words_per_probe = std::uint32_t(sh::packed_words(volume.sh_order()));
  out.words.assign(std::size_t(volume.probe_count()) * out.words_per_probe, 0);
  for (std::uint32_t i = 0; i < volume.probe_count(); ++i) {
    std::span<std::uint16_t> dst(out.words.data() + std::size_t(i) * out.words_per_probe,
                                 out.words_per_probe);
    const sh::ShRgb coefficients = volume.sh(i);
    const std::uint16_t flags = std::uint16_t(volume.state(i).flags & sh::kMetaFlagsMask);
    sh::PackFormat form = sh::PackFormat::kHalf;
    sh::PackStatus status = sh::PackStatus::kOk;
    switch (policy) {
      case EncodingPolicy::kAuto: status = sh::pack(coefficients, flags, dst, &form); break;
      case EncodingPolicy::kHalf: status = sh::pack_half(coefficients, flags, dst); break;
      case EncodingPolicy::kSharedExp:
        status = sh::pack_shared_exp(coefficients, flags, dst);
        form = sh::PackFormat::kSharedExp;
        break;
    }
    if (status == sh::PackStatus::kBadSize)
      throw std::logic_error("probe packing: output smaller than sh::packed_words");
    if (status != sh::PackStatus::kOk) ++out.overflowed_probes;
    if (severity(status) > severity(out.status)) out.status = status;
    (form == sh::PackFormat::kHalf ? out.half_probes : out.shared_exp_probes) += 1;
  }
  out.encoding = out.shared_exp_probes == 0 ? Encoding::kHalf
                 : out.half_probes == 0     ? Encoding::kSharedExp
                                            : Encoding::kMixed;
  return out;
}

sh::ShRgb unpack_probe(const PackedVolume& packed, std::uint32_t i) {
  return sh::unpack(packed.probe(i), packed.sh_order);
}

std::uint8_t unpack_flags(const PackedVolume& packed, std::uint32_t i) {
  return std::uint8_t(sh::packed_flags(packed.probe(i), packed.sh_order));
}

std::string encoding_name(Encoding encoding) {
  switch (encoding) {
    case Encoding::kHalf: return "fp16";
    case Encoding::kSharedExp: return "shared-exponent";
    case Encoding::kMixed: return "mixed";
  }
  return "unknown";
}

}  // namespace ddish::probes
