#include "raster/shader_variant.h"

#include "scene/features.h"

namespace ddish::raster {

ShaderVariant variant_for(const scene::RenderPlan& plan) {
  ShaderVariant v;
  v.direct_lights = plan.direct_lights;
  v.shadows = plan.direct_lights && (plan.shadow_maps || plan.point_shadows);
  v.textures = plan.texture_sampling;
  v.specular_probes = plan.specular_probes;
  v.emission = plan.emission;
  return v;
}

}  // namespace ddish::raster
