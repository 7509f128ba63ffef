#include "raster/view_method.h"

namespace ddish::raster {

std::string_view to_string(ViewMethod m) {
  switch (m) {
    case ViewMethod::per_view: return "per-view";
    case ViewMethod::multiview: return "multiview";
    case ViewMethod::layered: return "layered";
  }
  return "?";
}

std::optional<ViewMethod> parse_view_method(std::string_view name) {
  for (ViewMethod m : {ViewMethod::per_view, ViewMethod::multiview, ViewMethod::layered})
    if (name == to_string(m)) return m;
  return std::nullopt;
}

}  // namespace ddish::raster
