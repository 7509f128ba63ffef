// DDPV probe volume files (ddish probes --out) through the reader, unpacked into a volume and
// packed again.
#include "fuzz_support.h"
#include "probes/volume_file.h"
#include "probes/volume_packing.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = fuzz::as_file(data, size, "input.ddpv");
  fuzz::accepts([&] {
    const ddish::probes::VolumeFile file = ddish::probes::read_volume_file(path);
    const ddish::probes::ProbeVolume volume = file.to_volume();
    if (volume.probe_count() != file.grid.probe_count())
      fuzz::finding("volume size differs from the file's grid", path.c_str());
    ddish::probes::pack_volume(volume);
  });
  return 0;
}
