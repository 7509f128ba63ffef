// The private half of VkProbeTracer (vk_probe_tracer.h): the records its shaders read and write,
// and its GPU state. Shared by vk_probe_tracer.cpp (the update: batches, blends, read-back) and
// rt_pipeline.cpp (the ray-tracing pipeline, its shader binding table and descriptors); nothing
// outside trace_vk/ includes it.
#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "gpu/buffer.h"
#include "gpu/commands.h"
#include "gpu/compute_pipeline.h"
#include "gpu/device.h"
#include "gpu/handle.h"
#include "gpu/shader.h"
#include "gpu/transfer.h"
#include "scene/scene.h"
#include "trace_vk/acceleration.h"
#include "trace_vk/rt_functions.h"
#include "trace_vk/scene_layout.h"
#include "trace_vk/vk_probe_tracer.h"

namespace ddish::trace_vk {


inline constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
inline constexpr VkBufferUsageFlags kBuildInput = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                           VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR |
                                           VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
inline constexpr std::uint32_t kRtBindings = 18;  // trace_scene.glsl, trace_environment.glsl and probe_trace.rgen

// The shaders' per-work-item records (probe_trace.rgen, probe_project.comp).
struct ProbeWork {
  glm::vec4 origin{0.0f};  // w: the probe index's bits
  glm::vec4 rotation[3];
};
inline constexpr std::uint32_t kBlendDry = 1;  // report only: relocation's look before the update
struct Blend {
  std::uint32_t probe = 0;
  float weight = 1.0f;
  std::uint32_t backface_limit = ~0u;
  std::uint32_t flags = 0;
};
struct Result {
  std::uint32_t backfaces = 0;
  std::uint32_t invalid = 0;
  std::uint32_t inside = 0;
  std::uint32_t rays = 0;
  float nearest_back = 0.0f;  // of a probe being classified (infinity: none), and its path
  std::uint32_t back_path = ~0u;
  float nearest_front = 0.0f;
  std::uint32_t front_path = ~0u;
};
struct TraceParams {
  std::uint32_t samples, work_count, seed, frame;
  std::int32_t max_bounces, rr_min_bounces;
  float indirect_clamp;
  std::uint32_t light_count, emissive_count;
  float sky_r, sky_g, sky_b;
  GpuEnvironment environment;
};
struct ProjectParams {
  std::uint32_t samples, order, work_count, moment_resolution;
  float moment_range;
  float moment_scale;  // fixed-point steps per unit: no texel's sum of `samples` values overflows
};

inline VkDeviceSize align_up(VkDeviceSize v, VkDeviceSize a) { return (v + a - 1) / a * a; }

template <typename T>
gpu::Buffer make_buffer(const gpu::Device& device, gpu::CommandRunner& runner, const std::vector<T>& data,
                        VkBufferUsageFlags usage) {
  // A buffer cannot be empty: an empty list gets one zeroed element the shaders never read.
  const std::vector<T> one(1);
  const std::vector<T>& src = data.empty() ? one : data;
  gpu::Buffer b(device, src.size() * sizeof(T), usage, gpu::MemoryUse::device_local);
  gpu::upload(device, runner, b, src.data(), src.size() * sizeof(T));
  return b;
}

struct VkProbeTracer::Impl {
  Impl(const gpu::Device& d, const scene::Scene& s, const trace::PathOptions& p)
      : device(d), rt(d), runner(d), layout(SceneLayout::build(s)), path(p), sky(s.environment()) {
    vertices = make_buffer(d, runner, layout.vertices, kBuildInput);
    indices = make_buffer(d, runner, layout.indices, kBuildInput);
    meshes = make_buffer(d, runner, layout.meshes, kStorage);
    materials = make_buffer(d, runner, layout.materials, kStorage);
    albedo = make_buffer(d, runner, layout.albedo, kStorage);
    textures = make_buffer(d, runner, layout.textures, kStorage);
    texture_levels = make_buffer(d, runner, layout.texture_levels, kStorage);
    texels = make_buffer(d, runner, layout.texels, kStorage);
    environment_texels = make_buffer(d, runner, layout.environment_texels, kStorage);
    environment_cdf = make_buffer(d, runner, layout.environment_cdf, kStorage);
    place_buffers();
    acceleration = std::make_unique<SceneAcceleration>(d, rt, runner, vertices, indices, layout.meshes,
                                                       layout.materials, layout.instances, layout.deformed);
    make_rt_pipeline();
    project = std::make_unique<gpu::ComputePipeline>(d, gpu::ShaderModule::load(d, "probe_project.comp"),
                                                     gpu::ComputePipelineDesc{.storage_buffers = 8,
                                                                              .push_constant_bytes = sizeof(ProjectParams)});
  }

  void place_buffers() {
    instances = make_buffer(device, runner, layout.instances, kStorage);
    emissive = make_buffer(device, runner, layout.emissive, kStorage);
    lights = make_buffer(device, runner, layout.lights, kStorage);
  }

  void make_rt_pipeline();
  void write_descriptors();
  // Grows a per-update buffer to at least `bytes`.
  static void ensure(const gpu::Device& d, std::unique_ptr<gpu::Buffer>& b, VkDeviceSize bytes,
                     VkBufferUsageFlags usage, gpu::MemoryUse use) {
    if (!b || b->size() < bytes) b = std::make_unique<gpu::Buffer>(d, std::max<VkDeviceSize>(bytes, 16), usage, use);
  }

  const gpu::Device& device;
  RtFunctions rt;
  gpu::CommandRunner runner;
  SceneLayout layout;
  trace::PathOptions path;
  glm::vec3 sky;
  gpu::Buffer vertices, indices, meshes, materials, albedo, textures, texture_levels, texels, environment_texels,
      environment_cdf, instances, emissive, lights;
  std::unique_ptr<SceneAcceleration> acceleration;

  gpu::DeviceHandle<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout> set_layout;
  gpu::DeviceHandle<VkPipelineLayout, vkDestroyPipelineLayout> pipeline_layout;
  gpu::DeviceHandle<VkPipeline, vkDestroyPipeline> pipeline;
  gpu::DeviceHandle<VkDescriptorPool, vkDestroyDescriptorPool> pool;
  VkDescriptorSet set = VK_NULL_HANDLE;
  std::unique_ptr<gpu::Buffer> sbt;
  VkStridedDeviceAddressRegionKHR raygen_region{}, miss_region{}, hit_region{}, callable_region{};
  std::unique_ptr<gpu::ComputePipeline> project;

  // Traces and projects the probes of `items` in batches (TraceParams's and ProjectParams's
  // per-batch fields filled in here), blending into the GPU averages unless their blends are
  // dry; returns each item's result.
  std::vector<Result> trace(const std::vector<ProbeWork>& items, const std::vector<Blend>& blends, TraceParams tp,
                            ProjectParams pp);

  // Per-update buffers, grown as needed.
  std::unique_ptr<gpu::Buffer> lattice, work, paths, distances, blends, results, coefficients, moments;
  std::unique_ptr<gpu::Buffer> results_readback, coefficients_readback, moments_readback;
  std::uint32_t lattice_samples = 0;

  // The volume whose coefficients and moments the GPU buffers mirror, its update number then
  // and its moment resolution.
  const probes::ProbeVolume* mirrored = nullptr;
  std::uint64_t mirrored_frame = 0;
  int mirrored_moment_resolution = -1;
  std::uint64_t rays = 0;

  // defer_host_copy: the probes updated on the GPU whose host values are not (sorted and
  // unique after each update, so a run of hours keeps at most one entry a probe).
  bool defer = false;
  std::vector<std::uint32_t> stale;
  void compact_stale() {
    std::sort(stale.begin(), stale.end());
    stale.erase(std::unique(stale.begin(), stale.end()), stale.end());
  }
  // Copies the GPU's averages of the stale probes of `volume` (the mirrored one) into it.
  void copy_stale(probes::ProbeVolume& volume);
};

}  // namespace ddish::trace_vk
