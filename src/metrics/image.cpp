#include "metrics/image.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace ddish::metrics {

Image::Image(int width, int height, const glm::vec3& fill) {
  if (width < 0 || height < 0)
    throw std::invalid_argument("image size " + std::to_string(width) + "x" +
                                std::to_string(height) + " is negative");
  width_ = width;
  height_ = height;
  pixels_.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height), fill);
}

Image Image::crop(int x0, int y0, int w, int h) const {
  if (x0 < 0 || y0 < 0 || w < 0 || h < 0 || x0 + w > width_ || y0 + h > height_)
    throw std::out_of_range("crop " + std::to_string(w) + "x" + std::to_string(h) + " at (" +
                            std::to_string(x0) + "," + std::to_string(y0) +
                            ") leaves the " + std::to_string(width_) + "x" +
                            std::to_string(height_) + " image");
  Image out(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) out.at(x, y) = at(x0 + x, y0 + y);
  return out;
}

std::size_t Image::count_nonfinite() const {
  std::size_t n = 0;
  for (const glm::vec3& p : pixels_)
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) ++n;
  return n;
}

void require_same_size(const Image& image, const Image& reference) {
  if (image.width() == reference.width() && image.height() == reference.height()) return;
  throw std::invalid_argument("image is " + std::to_string(image.width()) + "x" +
                              std::to_string(image.height()) + ", reference is " +
                              std::to_string(reference.width()) + "x" +
                              std::to_string(reference.height()) +
                              ": images of different sizes cannot be compared");
}

}  // namespace ddish::metrics
