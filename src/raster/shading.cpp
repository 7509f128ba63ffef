#include "raster/shading.h"

namespace ddish::raster {

std::string_view to_string(Shading s) {
  switch (s) {
    case Shading::full: return "full";
    case Shading::trivial: return "trivial";
  }
  return "?";
}

std::optional<Shading> parse_shading(std::string_view name) {
  for (Shading s : {Shading::full, Shading::trivial})
    if (name == to_string(s)) return s;
  return std::nullopt;
}

}  // namespace ddish::raster
