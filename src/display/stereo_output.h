// Side-by-side stereo: the left eye's image on the left half, the right eye's on the right, the
// form stereo viewers, video players and headset mirror windows take.
#pragma once

#include "display/rgb_image.h"

namespace ddish::display {

// A (2 · width) × height image of two equally sized eye images. Throws std::invalid_argument
// when the eyes differ in size or are empty.
RgbImage side_by_side(ConstRgbView left, ConstRgbView right);

}  // namespace ddish::display
