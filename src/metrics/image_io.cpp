#include "metrics/image_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>

#include "io/atomic_file.h"
#include "metrics/color.h"

namespace ddish::metrics {

namespace {

// OpenImageIO error strings can span lines; ddish reports errors on one line.
std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

bool is_float_type(const OIIO::TypeDesc& t) {
  return t.basetype == OIIO::TypeDesc::FLOAT || t.basetype == OIIO::TypeDesc::HALF ||
         t.basetype == OIIO::TypeDesc::DOUBLE;
}

}  // namespace

Image read_image(const std::filesystem::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in)
    throw std::runtime_error("cannot read " + path.string() + ": " + one_line(OIIO::geterror()));
  const OIIO::ImageSpec& spec = in->spec();
  const int w = spec.width;
  const int h = spec.height;
  const int nch = spec.nchannels;
  if (w <= 0 || h <= 0 || nch <= 0)
    throw std::runtime_error("cannot read " + path.string() + ": empty image");
  // Integer files store display (sRGB-encoded) values; OpenImageIO hands them to us normalised
  // to [0, 1], and we decode them to linear here.
  const bool linear = is_float_type(spec.format);

  std::vector<float> data(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) *
                          static_cast<std::size_t>(nch));
  if (!in->read_image(0, 0, 0, nch, OIIO::TypeDesc::FLOAT, data.data()))
    throw std::runtime_error("cannot read " + path.string() + ": " + one_line(in->geterror()));
  in->close();

  Image image(w, h);
  auto decode = [linear](float v) { return linear ? v : srgb_decode(v); };
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const float* p = &data[(static_cast<std::size_t>(y) * static_cast<std::size_t>(w) +
                              static_cast<std::size_t>(x)) *
                             static_cast<std::size_t>(nch)];
      // One or two channels are grey (+ alpha): replicate grey into R, G and B.
      glm::vec3 rgb = nch >= 3 ? glm::vec3(p[0], p[1], p[2]) : glm::vec3(p[0]);
      image.at(x, y) = {decode(rgb.x), decode(rgb.y), decode(rgb.z)};
    }
  }
  return image;
}

namespace {

// Opens a temporary beside `path` for `spec` (the format plugin chosen by `path`'s extension),
// writes it row by row (`fill(y, buffer)` produces row y in `given`, the file's pixel format
// unless said otherwise: OpenImageIO converts) and renames it over `path` when complete
// (io/atomic_file.h: whole files only).
void write_rows(const std::filesystem::path& path, const OIIO::ImageSpec& spec,
                const std::function<void(int, void*)>& fill, OIIO::TypeDesc given = OIIO::TypeDesc::UNKNOWN) {
  if (given == OIIO::TypeDesc::UNKNOWN) given = spec.format;
  if (spec.width <= 0 || spec.height <= 0)
    throw std::invalid_argument("cannot write an empty image to " + path.string());
  io::write_atomically(path, [&](const std::filesystem::path& temporary) {
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out) throw std::runtime_error(one_line(OIIO::geterror()));
    std::vector<std::uint8_t> buffer(std::size_t(spec.width) * std::size_t(spec.nchannels) * given.size());
    errno = 0;
    bool ok = out->open(temporary.string(), spec);
    for (int y = 0; ok && y < spec.height; ++y) {
      fill(y, buffer.data());
      ok = out->write_scanline(y, 0, given, buffer.data());
    }
    if (!ok || !out->close()) {
      // The system's reason (a full disk, a size limit) says it best; the plugins' own messages
      // name the temporary and repeat themselves.
      const int error = errno;
      if (error != 0) throw std::runtime_error(std::strerror(error));
      std::string reason = one_line(out->geterror());
      for (std::size_t at; (at = reason.find(temporary.string())) != std::string::npos;)
        reason.replace(at, temporary.string().size(), path.string());
      throw std::runtime_error(reason.empty() ? "the image writer failed" : reason);
    }
  });
}

}  // namespace

void write_exr_rows(const std::filesystem::path& path, int width, int height, const LinearRow& row,
                    ExrPixels pixels) {
  const bool half = pixels == ExrPixels::half;
  OIIO::ImageSpec spec(width, height, 3, half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
  // Floats: zip at zlib level 1. The 10240x2880 Cornell quilt took 4.4 s over uncompressed
  // instead of 7.5 s at the default level 6, 56.5 MB instead of 47.3 MB (354 MB raw); piz
  // (5.0 s, 56.4 MB) and rle (1.4 s, 192 MB) measured no better balance.
  // Halves (the rasterizer's quilts, written while the next frames render on the same cores, so
  // their encoding time is frame time): rle. 48-view 3360x3360 quilts, oiiotool under load,
  // seconds over reading the input: Sponza rle 0.2-0.3 s / 59.6 MB, zip:1 1.0 s / 45.0 MB,
  // none 0.1-0.25 s / 67.8 MB; the Cornell box rle 0.6 s / 36.4 MB, zip:1 1.3 s / 20.7 MB.
  // Against the float zip:1 files before (Sponza 76.9 MB, Cornell 37.2 MB in 2.0 s) rle is
  // never larger and 3-7 times quicker.
  spec.attribute("compression", half ? "rle" : "zip:1");
  write_rows(path, spec, [&](int y, void* buffer) { row(y, static_cast<float*>(buffer)); },
             OIIO::TypeDesc::FLOAT);
}

void write_png_rows(const std::filesystem::path& path, int width, int height, const DisplayRow& row) {
  OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", "sRGB");
  // zlib level 1 (OpenImageIO's default is 6): a 10240x2880 quilt of the Cornell box took 1.8 s
  // more than an uncompressed write instead of 3.8 s, 8.2 MB instead of 5.1 MB (88.6 MB raw;
  // oiiotool on this 2-core machine, under load).
  spec.attribute("png:compressionLevel", 1);
  // Every row with the "up" filter instead of libpng's choice per row: a 3360x3360 Sponza quilt
  // took 1.19-1.41 s of CPU instead of 1.41-2.13 s (oiiotool, 3 runs each, with reading its
  // input), 14.9 MB instead of 14.3 MB; "sub" (15.5 MB) and none (16.4 MB) were no quicker.
  spec.attribute("png:filter", 32);  // PNG_FILTER_UP
  write_rows(path, spec, [&](int y, void* buffer) { row(y, static_cast<std::uint8_t*>(buffer)); });
}

void write_exr(const std::filesystem::path& path, const Image& image) {
  if (image.empty()) throw std::invalid_argument("cannot write an empty image to " + path.string());
  // glm::vec3 is three tightly packed floats, so the pixel vector is already interleaved RGB.
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
  const std::size_t w = static_cast<std::size_t>(image.width());
  write_exr_rows(path, image.width(), image.height(), [&](int y, float* rgb) {
    std::memcpy(rgb, &image.pixels()[std::size_t(y) * w].x, 3 * w * sizeof(float));
  });
}

void write_png(const std::filesystem::path& path, const Image& image) {
  if (image.empty()) throw std::invalid_argument("cannot write an empty image to " + path.string());
  const std::size_t w = static_cast<std::size_t>(image.width());
  write_png_rows(path, image.width(), image.height(), [&](int y, std::uint8_t* rgb) {
    const glm::vec3* p = &image.pixels()[std::size_t(y) * w];
    for (std::size_t x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) rgb[3 * x + std::size_t(c)] = srgb8_encode(p[x][c]);  // NaN: black
  });
}

void write_image(const std::filesystem::path& path, const Image& image) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".exr") return write_exr(path, image);
  if (ext == ".png") return write_png(path, image);
  throw std::invalid_argument("cannot write " + path.string() +
                              ": use .exr (linear) or .png (display)");
}

}  // namespace ddish::metrics
