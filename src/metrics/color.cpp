#include "metrics/color.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace ddish::metrics {

// Both directions are evaluated in double and rounded once, so 1 maps to exactly 1 (the display
// peak) and a decode/encode round trip returns the float it started from in nearly all cases.
float srgb_encode(float linear) {
  // The linear toe below 0.0031308 avoids the infinite slope of a pure power law at 0.
  if (linear <= 0.0031308f) return static_cast<float>(12.92 * double(linear));
  return static_cast<float>(1.055 * std::pow(double(linear), 1.0 / 2.4) - 0.055);
}

float srgb_decode(float encoded) {
  if (encoded <= 0.04045f) return static_cast<float>(double(encoded) / 12.92);
  return static_cast<float>(std::pow((double(encoded) + 0.055) / 1.055, 2.4));
}

namespace {
// Clamp that lets NaN through (std::clamp would return one of the bounds or be undefined).
float clamp01(float v) {
  if (v < 0.0f) return 0.0f;
  if (v > 1.0f) return 1.0f;
  return v;
}
}  // namespace

glm::vec3 display_value(const glm::vec3& linear) {
  return {srgb_encode(clamp01(linear.x)), srgb_encode(clamp01(linear.y)),
          srgb_encode(clamp01(linear.z))};
}

namespace {

struct Srgb8Tables {
  std::array<float, 256> decoded{};
  // midpoint[c]: the linear value half way between codes c and c + 1 in encoded space; a value
  // at or above it rounds to c + 1.
  std::array<float, 255> midpoint{};
  Srgb8Tables() {
    for (int c = 0; c < 256; ++c) decoded[std::size_t(c)] = srgb_decode(float(c) / 255.0f);
    for (int c = 0; c < 255; ++c) {
      const double e = (double(c) + 0.5) / 255.0;
      midpoint[std::size_t(c)] = static_cast<float>(
          e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4));
    }
  }
};

const Srgb8Tables& srgb8_tables() {
  static const Srgb8Tables tables;
  return tables;
}

}  // namespace

float srgb8_decode(std::uint8_t code) { return srgb8_tables().decoded[code]; }

std::span<const float, 255> srgb8_midpoints() { return srgb8_tables().midpoint; }

std::uint8_t srgb8_encode(float linear) {
  if (!(linear > 0.0f)) return 0;  // NaN and everything at or below 0
  const auto& m = srgb8_tables().midpoint;
  return static_cast<std::uint8_t>(std::upper_bound(m.begin(), m.end(), linear) - m.begin());
}

float luminance(const glm::vec3& rgb) {
  return 0.2126f * rgb.x + 0.7152f * rgb.y + 0.0722f * rgb.z;
}

}  // namespace ddish::metrics
