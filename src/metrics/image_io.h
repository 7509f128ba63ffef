// Reading and writing Images with OpenImageIO (DESIGN.md: PNG for display, EXR for linear data).
//
// Files hold either linear or display-encoded values, told apart by their pixel type: floating
// point files (EXR, HDR, PFM, float TIFF) are linear and read as they are; integer files (PNG,
// JPEG, 8/16-bit TIFF, PPM) hold sRGB-encoded values and are decoded to linear on reading. So an
// Image is always linear in memory, whichever kind of file it came from, and a PNG written by
// write_png reads back as the same display values.
//
// Writing is atomic (io/atomic_file.h): a file appears under its name complete or not at all;
// a failure throws std::runtime_error "cannot write PATH: REASON".
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>

#include "metrics/image.h"

namespace ddish::metrics {

// Reads any image OpenImageIO understands. One-channel (grey) and grey+alpha files are expanded
// to RGB; alpha and further channels are ignored. Throws std::runtime_error with a one-line
// message naming the file when it is missing or unreadable.
Image read_image(const std::filesystem::path& path);

// Linear 32-bit float RGB OpenEXR (ZIP compressed): values, NaN and infinities survive exactly.
void write_exr(const std::filesystem::path& path, const Image& image);

// 8-bit RGB PNG of the display values (clamped to [0, 1], sRGB-encoded, rounded to nearest).
void write_png(const std::filesystem::path& path, const Image& image);

// The same files from an image produced a row at a time (row 0 at the top), so that a large atlas
// composed from many views is never held whole: `row(y, out)` fills row y, 3 * width values.
// Rows are asked for in order, once each. Throws like the writers above, and
// std::invalid_argument for an empty size.
// The EXR holds 32-bit floats (zip), or with ExrPixels::half 16-bit halves (rle, the quicker
// encoding): exact for values that are halves already (the rasterizer's RGBA16F pixels), others
// rounded to the nearest half.
using LinearRow = std::function<void(int y, float* rgb)>;
using DisplayRow = std::function<void(int y, std::uint8_t* rgb)>;  // sRGB-encoded bytes
enum class ExrPixels { float32, half };
void write_exr_rows(const std::filesystem::path& path, int width, int height, const LinearRow& row,
                    ExrPixels pixels = ExrPixels::float32);
void write_png_rows(const std::filesystem::path& path, int width, int height, const DisplayRow& row);

// Chooses by extension (case-insensitive): ".exr" -> write_exr, ".png" -> write_png; anything
// else throws std::invalid_argument.
void write_image(const std::filesystem::path& path, const Image& image);

}  // namespace ddish::metrics
