#include "display/stereo_output.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace ddish::display {

RgbImage side_by_side(ConstRgbView left, ConstRgbView right) {
  if (left.width != right.width || left.height != right.height) {
    throw std::invalid_argument(
        "stereo eyes differ in size: left " + std::to_string(left.width) + "x" +
        std::to_string(left.height) + ", right " + std::to_string(right.width) + "x" +
        std::to_string(right.height));
  }
  if (left.width <= 0 || left.height <= 0) {
    throw std::invalid_argument("stereo eye images are empty");
  }
  RgbImage out(2 * left.width, left.height);
  const std::size_t row_floats = 3 * static_cast<std::size_t>(left.width);
  for (int y = 0; y < left.height; ++y) {
    std::copy_n(left.pixel(0, y), row_floats, out.pixel(0, y));
    std::copy_n(right.pixel(0, y), row_floats, out.pixel(left.width, y));
  }
  return out;
}

}  // namespace ddish::display
