// The images display outputs are composed from: linear RGB float triples, row by row, row 0 at the
// top (the order the rasterizer reads back and metrics::Image stores). display/ sits above
// metrics/ in the module order, so it cannot use metrics::Image; instead it works on these plain
// views of interleaved floats. A metrics::Image is a contiguous std::vector<glm::vec3> (three
// tightly packed floats per pixel), so the app wraps one without copying:
//   ConstRgbView{img.width(), img.height(), &img.pixels().data()->x}
#pragma once

#include <cstddef>
#include <vector>

namespace ddish::display {

// A read-only window onto width × height RGB pixels (3 floats each, rows top to bottom).
struct ConstRgbView {
  int width = 0;
  int height = 0;
  const float* data = nullptr;

  const float* pixel(int x, int y) const {
    return data + 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                       static_cast<std::size_t>(x));
  }
};

// A writable window onto width × height RGB pixels.
struct RgbView {
  int width = 0;
  int height = 0;
  float* data = nullptr;

  float* pixel(int x, int y) const {
    return data + 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                       static_cast<std::size_t>(x));
  }
  operator ConstRgbView() const { return ConstRgbView{width, height, data}; }
};

// An owning RGB image, black when created. Throws std::invalid_argument on negative sizes.
class RgbImage {
 public:
  RgbImage() = default;
  RgbImage(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  std::vector<float>& data() { return data_; }
  const std::vector<float>& data() const { return data_; }

  float* pixel(int x, int y) { return view().pixel(x, y); }
  const float* pixel(int x, int y) const { return view().pixel(x, y); }

  RgbView view() { return RgbView{width_, height_, data_.data()}; }
  ConstRgbView view() const { return ConstRgbView{width_, height_, data_.data()}; }

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<float> data_;
};

}  // namespace ddish::display
