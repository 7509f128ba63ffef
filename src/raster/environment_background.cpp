#include "raster/environment_background.h"

#include <cmath>
#include <vector>

#include <glm/glm.hpp>

#include "gpu/commands.h"
#include "gpu/shader.h"
#include "gpu/transfer.h"
#include "scene/environment_map.h"
#include "scene/view.h"

namespace ddish::raster {

namespace {

struct BackgroundParams {
  glm::mat4 inv_view_proj;
  glm::vec4 eye;
  glm::uvec4 size;  // view width, height, first pixel of the view in hdr, map width
  std::uint32_t map_height;
  float rotation_cos;
  float rotation_sin;
  float pad;
};
static_assert(sizeof(BackgroundParams) == 112, "the shader's push-constant block");

gpu::Buffer upload_texels(const gpu::Device& device, gpu::CommandRunner& runner,
                          const scene::EnvironmentMap& map) {
  std::vector<glm::vec4> texels;
  texels.reserve(map.texels.size());
  for (const glm::vec3& t : map.texels) texels.emplace_back(t, 0.0f);
  gpu::Buffer buffer(device, texels.size() * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                     gpu::MemoryUse::device_local);
  gpu::upload(device, runner, buffer, std::span<const glm::vec4>(texels));
  return buffer;
}

}  // namespace

EnvironmentBackground::EnvironmentBackground(const gpu::Device& device, gpu::CommandRunner& runner,
                                             const scene::EnvironmentMap& map)
    : texels_(upload_texels(device, runner, map)),
      pipeline_(device, gpu::ShaderModule::load(device, "environment_background.comp"),
                {.storage_buffers = 2, .push_constant_bytes = sizeof(BackgroundParams)}),
      map_width_(static_cast<std::uint32_t>(map.width)),
      map_height_(static_cast<std::uint32_t>(map.height)),
      rotation_(map.rotation) {}

void EnvironmentBackground::record(VkCommandBuffer cmd, const gpu::Buffer& hdr,
                                   std::span<const scene::View> views, std::uint32_t width,
                                   std::uint32_t height) {
  if (bound_hdr_ != hdr.handle()) {
    pipeline_.bind_buffers({&hdr, &texels_});
    bound_hdr_ = hdr.handle();
  }
  gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
  pipeline_.bind(cmd);
  const std::uint32_t pixels = width * height;
  for (std::size_t v = 0; v < views.size(); ++v) {
    const scene::View& view = views[v];
    BackgroundParams p{};
    p.inv_view_proj = glm::inverse(view.projection * view.view);
    p.eye = glm::vec4(view.eye(), 1.0f);
    p.size = {width, height, static_cast<std::uint32_t>(v) * pixels, map_width_};
    p.map_height = map_height_;
    p.rotation_cos = std::cos(rotation_);
    p.rotation_sin = std::sin(rotation_);
    pipeline_.push(cmd, p);
    pipeline_.dispatch(cmd, gpu::group_count(pixels, 64));
  }
  gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT |
                          VK_PIPELINE_STAGE_HOST_BIT,
                      VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_HOST_READ_BIT);
}

}  // namespace ddish::raster
