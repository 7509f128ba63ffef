// The forward pass: every instance drawn once per view with direct light, SH-probe indirect
// light and emission (forward_main.glsl), into an HDR target cleared to the environment's
// radiance (the uniform sky is what a pixel that hits nothing sees). It takes a list of views
// and a layered target, one layer per view: today each view is its own dynamic-rendering pass;
// a multiview path (one pass, gl_ViewIndex) can replace the loop without changing the interface.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "raster/graphics_pipeline.h"
#include "raster/shader_variant.h"

namespace ddish::gpu {
class Device;
}

namespace ddish::scene {
struct Scene;
}

namespace ddish::raster {

class GpuMeshes;
class MaterialTextures;
class RenderTarget;

// Descriptor sets in the order the shaders number them.
enum SetIndex : std::uint32_t { kFrameSet = 0, kProbeSet = 1, kBrdfSet = 2, kMaterialSet = 3 };

struct ForwardPassDesc {
  std::array<VkDescriptorSetLayout, 4> set_layouts{};  // by SetIndex
  int sh_order = 2;             // selects forward_sh<order>.frag
  std::uint32_t samples = 1;
  bool sample_shading = false;  // needs DeviceFeatures::sample_rate_shading
  ShaderVariant variant;
};

class ForwardPass {
 public:
  // Throws GpuError for a device without sample-rate shading when it is asked for, and for an
  // SH order outside 1..4.
  ForwardPass(const gpu::Device& device, const ForwardPassDesc& desc);

  // Records one pass per view into layer i of target: draws every instance of the scene.
  // sets holds the frame, probe and BRDF sets (SetIndex 0..2); materials give set 3.
  void record(VkCommandBuffer cmd, const scene::Scene& scene, const GpuMeshes& meshes,
              const MaterialTextures& materials, std::array<VkDescriptorSet, 3> sets,
              const RenderTarget& target, std::uint32_t views, const glm::vec3& environment);

  std::uint32_t passes_recorded() const { return passes_; }
  const ForwardPassDesc& desc() const { return desc_; }

 private:
  ForwardPassDesc desc_;
  PipelineLayout layout_;
  Pipeline pipeline_;
  std::uint32_t passes_ = 0;
};

}  // namespace ddish::raster
