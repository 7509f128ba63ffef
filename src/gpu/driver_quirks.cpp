#include "gpu/driver_quirks.h"

#include <cstdio>

namespace ddish::gpu {

std::optional<MesaVersion> mesa_version(const DeviceInfo& device) {
  const std::size_t at = device.driver_info.find("Mesa ");
  if (at == std::string::npos) return std::nullopt;
  MesaVersion v;
  if (std::sscanf(device.driver_info.c_str() + at + 5, "%d.%d", &v.major, &v.minor) != 2) return std::nullopt;
  return v;
}

bool is_lavapipe(const DeviceInfo& device) { return device.driver_name == "llvmpipe"; }

MultiviewDefect multiview_defect(const DeviceInfo& device) {
  if (!is_lavapipe(device)) return MultiviewDefect::none;
  const std::optional<MesaVersion> v = mesa_version(device);
  if (!v) return MultiviewDefect::none;
  if (v->major >= 25) return MultiviewDefect::timestamps_after_pass_overrun;
  if (v->major == 22) return MultiviewDefect::clipped_primitives_lose_view;
  return MultiviewDefect::none;
}

std::string describe(MultiviewDefect defect, const DeviceInfo& device) {
  switch (defect) {
    case MultiviewDefect::none: return {};
    case MultiviewDefect::clipped_primitives_lose_view:
      return "multiview on " + device.name + " (" + device.driver_info +
             ") draws primitives cut by the clipper into the pass's first view";
    case MultiviewDefect::timestamps_after_pass_overrun:
      return "after a multiview pass " + device.name + " (" + device.driver_info +
             ") writes one timestamp query per view of that pass, past the end of the pool; an "
             "empty one-view pass after the multiview passes avoids it";
  }
  return {};
}

}  // namespace ddish::gpu
