// An equirectangular (latitude-longitude) environment map: the radiance arriving from every
// direction at infinity, read from an HDR image (`--environment FILE`, app/lighting_options.h).
// Every renderer reads it through these conventions (docs/conventions.md):
// - Row 0 is the top of the image, +Y (up); the last row is -Y: v = acos(y) / pi.
// - The image's centre column (u = 0.5) is -Z, the way a glTF camera with no rotation looks;
//   u grows toward +X (to that camera's right), so the panorama is seen unmirrored from inside:
//   u = 0.5 + atan2(x, -z) / (2 pi); u = 0 and u = 1 are +Z.
// - Texels are linear radiance (W m^-2 sr^-1), multiplied by the intensity when the map is made.
// - The rotation turns the map about +Y by the right-hand rule (counter-clockwise seen from
//   above): what the file shows in direction d arrives from R_y(rotation) d.
// Lookups are bilinear between texel centres, wrapping around in u and clamped in v.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace ddish::scene {

struct EnvironmentMap {
  int width = 0;   // twice the height
  int height = 0;
  std::vector<glm::vec3> texels;  // row-major, row 0 at the top, intensity applied
  float rotation = 0.0f;          // radians about +Y
  float intensity = 1.0f;         // the factor already applied to texels (for the log)
  std::string source;             // the file it came from

  // Map coordinates (u, v) in [0, 1]^2 of a unit world direction, the rotation applied.
  glm::vec2 uv_of(const glm::vec3& direction) const;
  // The unit world direction at map coordinates (u, v), the rotation applied.
  glm::vec3 direction_of(const glm::vec2& uv) const;
  // Bilinear radiance arriving from a unit world direction.
  glm::vec3 radiance(const glm::vec3& direction) const;
  const glm::vec3& texel(int x, int y) const {
    return texels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                  static_cast<std::size_t>(x)];
  }
};

// A map from linear RGB texels (row 0 at the top). Throws std::invalid_argument naming `source`
// unless width is twice height (height >= 1), the texel count matches, every texel is finite and
// >= 0, intensity is finite and >= 0, and rotation_degrees is finite.
EnvironmentMap make_environment_map(int width, int height, std::vector<glm::vec3> texels,
                                    float rotation_degrees, float intensity,
                                    const std::string& source);

}  // namespace ddish::scene
