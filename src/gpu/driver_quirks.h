// Driver defects that change what ddish may do on a device, recognised by driver and version.
// Each is pinned by a test (tests/gpu/test_driver_quirks.cpp, tests/raster/multiview_test.cpp)
// that fails when a driver update removes it, so that the workaround is re-measured then.
#pragma once

#include <optional>
#include <string>

#include "gpu/device_info.h"

namespace ddish::gpu {

struct MesaVersion {
  int major = 0;
  int minor = 0;
};

// The Mesa release of a Mesa driver ("Mesa 25.0.7-2~bpo12+1 (LLVM 15.0.6)" -> 25.0), else none.
std::optional<MesaVersion> mesa_version(const DeviceInfo& device);

bool is_lavapipe(const DeviceInfo& device);

enum class MultiviewDefect {
  none,
  // lavapipe of Mesa 22: a primitive that the clipper cuts (near plane, beyond the guard band)
  // loses its view index and lands in the pass's first view. Exact while nothing is clipped.
  clipped_primitives_lose_view,
  // lavapipe of Mesa 25 (seen on 25.0.7, assumed for later releases until re-measured): after a
  // dynamic-rendering pass with a view mask of n views has ended, the driver still writes n
  // consecutive queries for every vkCmdWriteTimestamp, so a timestamp into one of the last n-1
  // queries of a pool writes past its end and kills the driver's queue thread (SIGSEGV in
  // libvulkan_lvp.so); validation reports nothing. An empty one-view pass after the multiview
  // passes clears the driver's view mask (raster/forward_pass.cpp records one).
  timestamps_after_pass_overrun,
};

MultiviewDefect multiview_defect(const DeviceInfo& device);

// One sentence for an error or a log line; empty for MultiviewDefect::none.
std::string describe(MultiviewDefect defect, const DeviceInfo& device);

}  // namespace ddish::gpu
