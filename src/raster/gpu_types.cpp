#include "raster/gpu_types.h"

namespace ddish::raster {

DrawConstants draw_constants(const glm::mat4& model, std::uint32_t view_index,
                             std::uint32_t material) {
  DrawConstants c;
  c.model = model;
  const glm::mat3 m(model);
  const glm::mat3 normal = glm::transpose(glm::inverse(m));
  for (int i = 0; i < 3; ++i) c.normal_matrix[i] = glm::vec4(normal[i], 0.0f);
  c.normal_matrix[0].w = glm::determinant(m) < 0.0f ? -1.0f : 1.0f;
  c.view_index = view_index;
  c.material = material;
  return c;
}

}  // namespace ddish::raster
