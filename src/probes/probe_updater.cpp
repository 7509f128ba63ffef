#include "probes/probe_updater.h"

#include <numeric>
#include <stdexcept>
#include <string>

#include "probes/probe_tracer.h"

namespace ddish::probes {

UpdateStats ProbeUpdater::update_all(ProbeVolume& volume) const {
  std::vector<std::uint32_t> all(volume.probe_count());
  std::iota(all.begin(), all.end(), 0u);
  return update(volume, all);
}

std::vector<std::uint32_t> probes_to_update(const ProbeVolume& volume,
                                            std::span<const std::uint32_t> probes) {
  std::vector<std::uint32_t> work;
  work.reserve(probes.size());
  std::vector<bool> listed(volume.probe_count(), false);
  for (std::uint32_t p : probes) {
    if (p >= volume.probe_count())
      throw std::out_of_range("probe index " + std::to_string(p) + " outside a volume of " +
                              std::to_string(volume.probe_count()) + " probes");
    if (volume.state(p).active() && !listed[p]) work.push_back(p);
    listed[p] = true;
  }
  return work;
}

}  // namespace ddish::probes
