// Display encoding shared by the PNG writer and the display-referred metrics (PSNR, SSIM):
// linear values are clamped to [0, 1] and encoded with the sRGB transfer function (IEC 61966-2-1),
// without any tone curve, so "display values" mean exactly what an sRGB PNG of the image holds.
#pragma once

#include <cstdint>
#include <span>

#include <glm/glm.hpp>

namespace ddish::metrics {

// sRGB opto-electronic transfer function for one linear value in [0, 1] (not clamped).
float srgb_encode(float linear);
// Its inverse: an sRGB-encoded value in [0, 1] back to linear.
float srgb_decode(float encoded);

// The display value of a linear colour: each channel clamped to [0, 1], then sRGB-encoded.
// NaN stays NaN, so a broken image shows up in the metrics instead of being hidden.
glm::vec3 display_value(const glm::vec3& linear);

// The 8-bit codes of a PNG, through tables (no pow per pixel: the frame writer converts tens of
// millions of channels a frame). srgb8_decode(c) is srgb_decode(c / 255). srgb8_encode clamps to
// [0, 1], sRGB-encodes and rounds to the nearest code (NaN -> 0): the same code as
// lround(255 * srgb_encode(v)) except within a float step of a code boundary, and exactly the
// inverse of srgb8_decode (srgb8_encode(srgb8_decode(c)) == c for every c).
float srgb8_decode(std::uint8_t code);
std::uint8_t srgb8_encode(float linear);
// srgb8_encode's thresholds: a value at or above midpoint c (0..254) encodes to more than c. With
// the 256 decoded values they let a GPU pass encode exactly as srgb8_encode does.
std::span<const float, 255> srgb8_midpoints();

// Rec. 709 / sRGB luma weights (0.2126, 0.7152, 0.0722) applied to whatever values it is given;
// SSIM applies it to display values.
float luminance(const glm::vec3& rgb);

}  // namespace ddish::metrics
