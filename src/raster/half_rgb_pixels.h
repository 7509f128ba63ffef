// A view's linear RGB pixels kept as the 16-bit halves its RGBA16F render target holds: 6 bytes a
// pixel where float RGB takes 12, and exact, since every value was a half on the device already.
// Reads give floats. The frame loop holds two frames' images while the writer encodes the last
// one (app/output_queue.h), so this halves the largest term of a many-view run's memory.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iterator>
#include <vector>

#include <glm/glm.hpp>

#include "sh/packing.h"

namespace ddish::raster {

class HalfRgbPixels {
 public:
  HalfRgbPixels() = default;
  // `count` black pixels.
  explicit HalfRgbPixels(std::size_t count) : halves_(3 * count, 0) {}

  std::size_t size() const { return halves_.size() / 3; }
  bool empty() const { return halves_.empty(); }

  glm::vec3 operator[](std::size_t i) const {
    const std::uint16_t* p = &halves_[3 * i];
    return {sh::half_to_float(p[0]), sh::half_to_float(p[1]), sh::half_to_float(p[2])};
  }
  // Pixels [first, first + count) as 3 * count floats.
  void read(std::size_t first, std::size_t count, float* rgb) const {
    const std::uint16_t* p = &halves_[3 * first];
    for (std::size_t i = 0; i < 3 * count; ++i) rgb[i] = sh::half_to_float(p[i]);
  }
  std::vector<glm::vec3> to_floats() const {
    std::vector<glm::vec3> out(size());
    if (!out.empty()) read(0, out.size(), &out[0].x);
    return out;
  }

  // RGB halves, pixel after pixel: what the renderer fills.
  std::uint16_t* halves() { return halves_.data(); }
  const std::uint16_t* halves() const { return halves_.data(); }

  // Bit for bit: two renders that agree hold the same halves.
  bool operator==(const HalfRgbPixels&) const = default;

  // Iterates the pixels as floats (for (glm::vec3 p : pixels)).
  class const_iterator {
   public:
    using iterator_category = std::input_iterator_tag;
    using value_type = glm::vec3;
    using difference_type = std::ptrdiff_t;
    using pointer = void;
    using reference = glm::vec3;
    const_iterator(const HalfRgbPixels* pixels, std::size_t i) : pixels_(pixels), i_(i) {}
    glm::vec3 operator*() const { return (*pixels_)[i_]; }
    const_iterator& operator++() { ++i_; return *this; }
    bool operator==(const const_iterator& o) const { return i_ == o.i_; }

   private:
    const HalfRgbPixels* pixels_;
    std::size_t i_;
  };
  const_iterator begin() const { return {this, 0}; }
  const_iterator end() const { return {this, size()}; }

 private:
  std::vector<std::uint16_t> halves_;
};

}  // namespace ddish::raster
