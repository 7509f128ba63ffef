// A linear RGB float image: what the reference renderer produces and what every error metric
// reads. Row 0 is the top of the image (the order OpenImageIO and the rasterizer use), pixels are
// stored row by row. Values are linear radiance-like quantities; display encoding (sRGB) is
// applied only where a metric or a PNG asks for it (see color.h).
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

namespace ddish::metrics {

class Image {
 public:
  Image() = default;
  // A width × height image filled with `fill`. Throws std::invalid_argument on negative sizes.
  Image(int width, int height, const glm::vec3& fill = glm::vec3(0.0f));

  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t pixel_count() const { return pixels_.size(); }
  bool empty() const { return pixels_.empty(); }

  glm::vec3& at(int x, int y) { return pixels_[index(x, y)]; }
  const glm::vec3& at(int x, int y) const { return pixels_[index(x, y)]; }

  // Row-major pixels, row 0 first (the top of the image).
  std::vector<glm::vec3>& pixels() { return pixels_; }
  const std::vector<glm::vec3>& pixels() const { return pixels_; }

  // Copies a w × h region whose top-left corner is (x0, y0); throws std::out_of_range when the
  // region leaves the image. Multi-view atlases (quilts) are split into views with it.
  Image crop(int x0, int y0, int w, int h) const;

  // Number of pixels with a NaN or infinite channel.
  std::size_t count_nonfinite() const;

 private:
  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
           static_cast<std::size_t>(x);
  }

  int width_ = 0;
  int height_ = 0;
  std::vector<glm::vec3> pixels_;
};

// Throws std::invalid_argument with a one-line message ("image is 64x32, reference is 64x64")
// unless both images have the same size. Every metric calls it first.
void require_same_size(const Image& image, const Image& reference);

}  // namespace ddish::metrics
