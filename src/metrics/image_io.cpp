#include "metrics/image_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <cstdint>
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

// Whole files only (io/atomic_file.h): the image is encoded into a temporary beside `path`,
// with the format plugin chosen by `path`'s extension, and renamed when complete.
void write_spec(const std::filesystem::path& path, const OIIO::ImageSpec& spec,
                const void* data) {
  io::write_atomically(path, [&](const std::filesystem::path& temporary) {
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out) throw std::runtime_error(one_line(OIIO::geterror()));
    errno = 0;
    if (!out->open(temporary.string(), spec) || !out->write_image(spec.format, data) ||
        !out->close()) {
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

void write_exr(const std::filesystem::path& path, const Image& image) {
  if (image.empty()) throw std::invalid_argument("cannot write an empty image to " + path.string());
  OIIO::ImageSpec spec(image.width(), image.height(), 3, OIIO::TypeDesc::FLOAT);
  spec.attribute("compression", "zip");
  // glm::vec3 is three tightly packed floats, so the pixel vector is already interleaved RGB.
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
  write_spec(path, spec, image.pixels().data());
}

void write_png(const std::filesystem::path& path, const Image& image) {
  if (image.empty()) throw std::invalid_argument("cannot write an empty image to " + path.string());
  std::vector<std::uint8_t> bytes;
  bytes.reserve(image.pixel_count() * 3);
  for (const glm::vec3& p : image.pixels()) {
    glm::vec3 d = display_value(p);
    for (int c = 0; c < 3; ++c) {
      // NaN would make the cast undefined; a broken pixel is written black.
      float v = std::isnan(d[c]) ? 0.0f : d[c];
      bytes.push_back(static_cast<std::uint8_t>(std::lround(v * 255.0f)));
    }
  }
  OIIO::ImageSpec spec(image.width(), image.height(), 3, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", "sRGB");
  write_spec(path, spec, bytes.data());
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
