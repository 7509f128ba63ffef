// The single view: one ordinary perspective camera (a monitor, a reference image).
#pragma once

#include "display/view_set.h"

namespace ddish::display {

// One symmetric view of `base` at width × height pixels, its projection built for `aspect`
// (width / height when aspect <= 0). Layout 1 × 1.
ViewSet single_view(const BaseCamera& base, int width, int height, float aspect = 0.0f);

}  // namespace ddish::display
