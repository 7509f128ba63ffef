#include "scene/environment_map.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <sstream>

namespace ddish::scene {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

template <typename... T>
std::string cat(const T&... parts) {
  std::ostringstream out;
  (out << ... << parts);
  return out.str();
}

}  // namespace

glm::vec2 EnvironmentMap::uv_of(const glm::vec3& d) const {
  // The file's direction: the world direction turned back by the rotation, R_y(-rotation) d.
  const float c = std::cos(rotation);
  const float s = std::sin(rotation);
  const float x = c * d.x - s * d.z;
  const float z = s * d.x + c * d.z;
  float u = 0.5f + std::atan2(x, -z) / (2.0f * kPi);
  if (!(u >= 0.0f)) u = 0.0f;  // NaN, and -0 rounding
  if (u > 1.0f) u = 1.0f;
  const float v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) / kPi;
  return {u, v};
}

glm::vec3 EnvironmentMap::direction_of(const glm::vec2& uv) const {
  const float theta = uv.y * kPi;
  const float phi = (uv.x - 0.5f) * 2.0f * kPi;
  const float st = std::sin(theta);
  const float xf = st * std::sin(phi);
  const float zf = -st * std::cos(phi);
  const float c = std::cos(rotation);
  const float s = std::sin(rotation);
  return {c * xf + s * zf, std::cos(theta), -s * xf + c * zf};
}

glm::vec3 EnvironmentMap::radiance(const glm::vec3& direction) const {
  const glm::vec2 uv = uv_of(direction);
  const float fx = uv.x * static_cast<float>(width) - 0.5f;
  const float fy = std::clamp(uv.y * static_cast<float>(height) - 0.5f, 0.0f,
                              static_cast<float>(height - 1));
  const float x0f = std::floor(fx);
  const float y0f = std::floor(fy);
  const float tx = fx - x0f;
  const float ty = fy - y0f;
  const int x0 = ((static_cast<int>(x0f) % width) + width) % width;
  const int x1 = (x0 + 1) % width;
  const int y0 = static_cast<int>(y0f);
  const int y1 = std::min(y0 + 1, height - 1);
  const glm::vec3 top = glm::mix(texel(x0, y0), texel(x1, y0), tx);
  const glm::vec3 bottom = glm::mix(texel(x0, y1), texel(x1, y1), tx);
  return glm::mix(top, bottom, ty);
}

EnvironmentMap make_environment_map(int width, int height, std::vector<glm::vec3> texels,
                                    float rotation_degrees, float intensity,
                                    const std::string& source) {
  if (height < 1 || width != 2 * height)
    throw std::invalid_argument(cat(source,
                                    ": an equirectangular environment map is twice as wide as it "
                                    "is high, this one is ",
                                    width, "x", height));
  if (texels.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
    throw std::invalid_argument(cat(source, ": ", texels.size(), " texels for ", width, "x", height));
  if (!std::isfinite(intensity) || intensity < 0.0f)
    throw std::invalid_argument(
        cat("--environment-intensity must be a finite number >= 0, got ", intensity));
  if (!std::isfinite(rotation_degrees))
    throw std::invalid_argument("--environment-rotation must be a finite angle in degrees");
  for (glm::vec3& t : texels) {
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(t[c]) || t[c] < 0.0f)
        throw std::invalid_argument(
            cat(source, ": texel values must be finite radiances >= 0 (found ", t[c], ")"));
    }
    t *= intensity;
  }
  EnvironmentMap m;
  m.width = width;
  m.height = height;
  m.texels = std::move(texels);
  m.rotation = glm::radians(std::fmod(rotation_degrees, 360.0f));
  m.intensity = intensity;
  m.source = source;
  return m;
}

}  // namespace ddish::scene
