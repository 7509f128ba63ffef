// The run log's line per frame of `render` and `view` (stderr): the frame's probe work, raster
// and output times from its report, the stream's state when the probes come from a server, and
// on frame 0 how many probes classification found inside geometry.
#pragma once

#include "app/frame_loop.h"

namespace ddish::app {

void print_progress(const FrameReport& report, int frames);

}  // namespace ddish::app
