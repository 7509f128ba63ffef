#include "display/rgb_image.h"

#include <stdexcept>
#include <string>

namespace ddish::display {

RgbImage::RgbImage(int width, int height) : width_(width), height_(height) {
  if (width < 0 || height < 0) {
    throw std::invalid_argument("image size " + std::to_string(width) + "x" +
                                std::to_string(height) + " is negative");
  }
  data_.assign(3 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height), 0.0f);
}

}  // namespace ddish::display
