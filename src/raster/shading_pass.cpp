#include "raster/shading_pass.h"

namespace ddish::raster {

std::string_view to_string(ShadingPass p) {
  switch (p) {
    case ShadingPass::forward: return "forward";
    case ShadingPass::visibility: return "visibility";
  }
  return "?";
}

std::optional<ShadingPass> parse_shading_pass(std::string_view name) {
  for (ShadingPass p : {ShadingPass::forward, ShadingPass::visibility})
    if (name == to_string(p)) return p;
  return std::nullopt;
}

}  // namespace ddish::raster
