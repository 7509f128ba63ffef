#include "trace_vk/vk_probe_tracer.h"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cstring>
#include <stdexcept>

#include "gpu/commands.h"
#include "gpu/compute_pipeline.h"
#include "gpu/device.h"
#include "gpu/error.h"
#include "gpu/handle.h"
#include "gpu/shader.h"
#include "gpu/transfer.h"
#include "probes/accumulation.h"
#include "probes/classification.h"
#include "probes/fibonacci.h"
#include "scene/scene.h"
#include "trace/sampler.h"
#include "trace_vk/acceleration.h"
#include "trace_vk/rt_functions.h"
#include "trace_vk/scene_layout.h"

namespace ddish::trace_vk {

namespace {

constexpr VkBufferUsageFlags kStorage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
constexpr VkBufferUsageFlags kBuildInput = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                           VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR |
                                           VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
constexpr std::uint32_t kRtBindings = 18;  // trace_scene.glsl, trace_environment.glsl and probe_trace.rgen

// The shaders' per-work-item records (probe_trace.rgen, probe_project.comp).
struct ProbeWork {
  glm::vec4 origin{0.0f};  // w: the probe index's bits
  glm::vec4 rotation[3];
};
constexpr std::uint32_t kBlendDry = 1;  // report only: relocation's look before the update
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

VkDeviceSize align_up(VkDeviceSize v, VkDeviceSize a) { return (v + a - 1) / a * a; }

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

// The most back-face first hits of N rays that still leave a probe outside geometry
// (probes::classify's rule, found with its own arithmetic so both sides agree exactly).
std::uint32_t backface_limit(std::uint32_t rays, float threshold) {
  std::uint32_t k = static_cast<std::uint32_t>(std::min<double>(double(threshold) * rays, rays));
  while (k > 0 && probes::classify(k, rays, threshold).inside_geometry) --k;
  while (k < rays && !probes::classify(k + 1, rays, threshold).inside_geometry) ++k;
  return k;
}

// A batch's bounds: 4 Mi paths (64 MiB of path records), and work groups within every device's
// minimum maxComputeWorkGroupCount (65535).
constexpr std::size_t kMaxBatchPaths = std::size_t{1} << 22;
constexpr std::size_t kMaxBatchProbes = 65535;

std::uint32_t fold(std::uint64_t v) { return static_cast<std::uint32_t>(v ^ (v >> 32)); }

}  // namespace

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

void VkProbeTracer::Impl::copy_stale(probes::ProbeVolume& volume) {
  if (stale.empty()) return;
  compact_stale();
  const auto coeffs = std::size_t(volume.coefficient_count());
  const auto map_texels = std::size_t(volume.moment_texels());
  const VkDeviceSize coefficient_bytes = VkDeviceSize(volume.probe_count()) * coeffs * sizeof(glm::vec3);
  const VkDeviceSize moment_bytes = VkDeviceSize(volume.probe_count()) * map_texels * sizeof(glm::vec2);
  ensure(device, coefficients_readback, coefficient_bytes, kStorage, gpu::MemoryUse::readback);
  ensure(device, moments_readback, moment_bytes, kStorage, gpu::MemoryUse::readback);
  runner.run([&](VkCommandBuffer cmd) {
    gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
                        VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
    gpu::copy_buffer(cmd, *coefficients, *coefficients_readback, coefficient_bytes);
    if (moment_bytes > 0) gpu::copy_buffer(cmd, *moments, *moments_readback, moment_bytes);
    gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                        VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
  });
  const auto* gpu_coefficients = static_cast<const glm::vec3*>(coefficients_readback->mapped());
  const auto* gpu_moments = static_cast<const glm::vec2*>(moments_readback->mapped());
  for (std::uint32_t p : stale) {
    const auto dst = volume.coefficients(p);
    std::memcpy(dst.data(), gpu_coefficients + std::size_t(p) * coeffs, coeffs * sizeof(glm::vec3));
    const auto m = volume.moments(p);
    if (!m.empty()) std::memcpy(m.data(), gpu_moments + std::size_t(p) * map_texels, m.size_bytes());
  }
  stale.clear();
}

void VkProbeTracer::Impl::make_rt_pipeline() {
  const VkDevice d = device.handle();
  std::array<VkDescriptorSetLayoutBinding, kRtBindings> bindings{};
  for (std::uint32_t i = 0; i < kRtBindings; ++i) {
    bindings[i].binding = i;
    bindings[i].descriptorType =
        i == 0 ? VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    bindings[i].descriptorCount = 1;
    bindings[i].stageFlags = VK_SHADER_STAGE_RAYGEN_BIT_KHR | VK_SHADER_STAGE_ANY_HIT_BIT_KHR;
  }
  VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  set_info.bindingCount = kRtBindings;
  set_info.pBindings = bindings.data();
  VkDescriptorSetLayout sl = VK_NULL_HANDLE;
  gpu::check(vkCreateDescriptorSetLayout(d, &set_info, nullptr, &sl), "vkCreateDescriptorSetLayout");
  set_layout = {d, sl};

  const VkPushConstantRange push{VK_SHADER_STAGE_RAYGEN_BIT_KHR, 0, sizeof(TraceParams)};
  VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layout_info.setLayoutCount = 1;
  layout_info.pSetLayouts = &sl;
  layout_info.pushConstantRangeCount = 1;
  layout_info.pPushConstantRanges = &push;
  VkPipelineLayout pl = VK_NULL_HANDLE;
  gpu::check(vkCreatePipelineLayout(d, &layout_info, nullptr, &pl), "vkCreatePipelineLayout");
  pipeline_layout = {d, pl};

  const gpu::ShaderModule raygen = gpu::ShaderModule::load(device, "probe_trace.rgen");
  const gpu::ShaderModule miss = gpu::ShaderModule::load(device, "probe_trace.rmiss");
  const gpu::ShaderModule shadow_miss = gpu::ShaderModule::load(device, "probe_shadow.rmiss");
  const gpu::ShaderModule closest = gpu::ShaderModule::load(device, "probe_trace.rchit");
  const gpu::ShaderModule any = gpu::ShaderModule::load(device, "probe_trace.rahit");
  const gpu::ShaderModule shadow_any = gpu::ShaderModule::load(device, "probe_shadow.rahit");
  std::array<VkPipelineShaderStageCreateInfo, 6> stages{};
  const std::array<std::pair<VkShaderStageFlagBits, VkShaderModule>, 6> modules = {{
      {VK_SHADER_STAGE_RAYGEN_BIT_KHR, raygen.handle()},
      {VK_SHADER_STAGE_MISS_BIT_KHR, miss.handle()},
      {VK_SHADER_STAGE_MISS_BIT_KHR, shadow_miss.handle()},
      {VK_SHADER_STAGE_CLOSEST_HIT_BIT_KHR, closest.handle()},
      {VK_SHADER_STAGE_ANY_HIT_BIT_KHR, any.handle()},
      {VK_SHADER_STAGE_ANY_HIT_BIT_KHR, shadow_any.handle()},
  }};
  for (std::size_t i = 0; i < stages.size(); ++i) {
    stages[i] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
    stages[i].stage = modules[i].first;
    stages[i].module = modules[i].second;
    stages[i].pName = "main";
  }
  // Groups: raygen, path miss, shadow miss, then two hit groups: path rays (closest hit and
  // any-hit, SBT offset 0) and shadow rays (any-hit only, SBT offset 1).
  std::array<VkRayTracingShaderGroupCreateInfoKHR, 5> groups{};
  for (std::uint32_t i = 0; i < groups.size(); ++i) {
    groups[i] = {VK_STRUCTURE_TYPE_RAY_TRACING_SHADER_GROUP_CREATE_INFO_KHR};
    groups[i].type = i < 3 ? VK_RAY_TRACING_SHADER_GROUP_TYPE_GENERAL_KHR
                           : VK_RAY_TRACING_SHADER_GROUP_TYPE_TRIANGLES_HIT_GROUP_KHR;
    groups[i].generalShader = i < 3 ? i : VK_SHADER_UNUSED_KHR;
    groups[i].closestHitShader = i == 3 ? 3 : VK_SHADER_UNUSED_KHR;
    groups[i].anyHitShader = i == 3 ? 4 : i == 4 ? 5 : VK_SHADER_UNUSED_KHR;
    groups[i].intersectionShader = VK_SHADER_UNUSED_KHR;
  }
  VkRayTracingPipelineCreateInfoKHR info{VK_STRUCTURE_TYPE_RAY_TRACING_PIPELINE_CREATE_INFO_KHR};
  info.stageCount = static_cast<std::uint32_t>(stages.size());
  info.pStages = stages.data();
  info.groupCount = static_cast<std::uint32_t>(groups.size());
  info.pGroups = groups.data();
  info.maxPipelineRayRecursionDepth = 1;  // only the ray generation shader traces
  info.layout = pl;
  VkPipeline p = VK_NULL_HANDLE;
  gpu::check(rt.create_pipelines(d, VK_NULL_HANDLE, VK_NULL_HANDLE, 1, &info, nullptr, &p),
             "vkCreateRayTracingPipelinesKHR");
  pipeline = {d, p};

  // The shader binding table: raygen, the two misses, the hit group, each region aligned.
  VkPhysicalDeviceRayTracingPipelinePropertiesKHR rtp{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_TRACING_PIPELINE_PROPERTIES_KHR};
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props.pNext = &rtp;
  vkGetPhysicalDeviceProperties2(device.physical(), &props);
  const VkDeviceSize handle_size = rtp.shaderGroupHandleSize;
  const VkDeviceSize base = rtp.shaderGroupBaseAlignment;
  const VkDeviceSize stride = align_up(handle_size, rtp.shaderGroupHandleAlignment);
  std::vector<std::uint8_t> handles(groups.size() * handle_size);
  gpu::check(rt.get_group_handles(d, p, 0, static_cast<std::uint32_t>(groups.size()), handles.size(), handles.data()),
             "vkGetRayTracingShaderGroupHandlesKHR");
  const VkDeviceSize raygen_size = align_up(stride, base);
  const VkDeviceSize miss_offset = raygen_size;
  const VkDeviceSize miss_size = align_up(2 * stride, base);
  const VkDeviceSize hit_offset = miss_offset + miss_size;
  const VkDeviceSize hit_size = align_up(2 * stride, base);
  sbt = std::make_unique<gpu::Buffer>(
      device, hit_offset + hit_size + base,
      VK_BUFFER_USAGE_SHADER_BINDING_TABLE_BIT_KHR | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT, gpu::MemoryUse::upload);
  const VkDeviceAddress address = align_up(sbt->device_address(), base);
  const VkDeviceSize shift = address - sbt->device_address();
  sbt->write(handles.data() + 0 * handle_size, handle_size, shift);
  sbt->write(handles.data() + 1 * handle_size, handle_size, shift + miss_offset);
  sbt->write(handles.data() + 2 * handle_size, handle_size, shift + miss_offset + stride);
  sbt->write(handles.data() + 3 * handle_size, handle_size, shift + hit_offset);
  sbt->write(handles.data() + 4 * handle_size, handle_size, shift + hit_offset + stride);
  raygen_region = {address, raygen_size, raygen_size};
  miss_region = {address + miss_offset, stride, miss_size};
  hit_region = {address + hit_offset, stride, hit_size};

  const std::array<VkDescriptorPoolSize, 2> sizes = {{{VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR, 1},
                                                      {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, kRtBindings - 1}}};
  VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pool_info.maxSets = 1;
  pool_info.poolSizeCount = static_cast<std::uint32_t>(sizes.size());
  pool_info.pPoolSizes = sizes.data();
  VkDescriptorPool dp = VK_NULL_HANDLE;
  gpu::check(vkCreateDescriptorPool(d, &pool_info, nullptr, &dp), "vkCreateDescriptorPool");
  pool = {d, dp};
  VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  alloc.descriptorPool = dp;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &sl;
  gpu::check(vkAllocateDescriptorSets(d, &alloc, &set), "vkAllocateDescriptorSets");
}

void VkProbeTracer::Impl::write_descriptors() {
  const VkAccelerationStructureKHR tlas = acceleration->tlas();
  VkWriteDescriptorSetAccelerationStructureKHR as{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR};
  as.accelerationStructureCount = 1;
  as.pAccelerationStructures = &tlas;
  const std::array<const gpu::Buffer*, kRtBindings - 1> buffers = {
      paths.get(), work.get(), &vertices, &indices, &meshes, &instances, &materials, &emissive, &lights, &albedo,
      lattice.get(), &textures, &texture_levels, &texels, &environment_texels, &environment_cdf, distances.get()};
  std::array<VkDescriptorBufferInfo, kRtBindings - 1> infos{};
  std::array<VkWriteDescriptorSet, kRtBindings> writes{};
  writes[0] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  writes[0].pNext = &as;
  writes[0].dstSet = set;
  writes[0].dstBinding = 0;
  writes[0].descriptorCount = 1;
  writes[0].descriptorType = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR;
  for (std::uint32_t i = 1; i < kRtBindings; ++i) {
    infos[i - 1] = buffers[i - 1]->descriptor();
    writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[i].dstSet = set;
    writes[i].dstBinding = i;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &infos[i - 1];
  }
  vkUpdateDescriptorSets(device.handle(), kRtBindings, writes.data(), 0, nullptr);
  project->bind_buffers({paths.get(), lattice.get(), work.get(), blends.get(), coefficients.get(), results.get(),
                         distances.get(), moments.get()});
}

VkProbeTracer::VkProbeTracer(const gpu::Device& device, const scene::Scene& scene, const trace::PathOptions& path,
                             const probes::UpdateOptions& options)
    : options_(options) {
  probes::check_update_options(options);
  impl_ = std::make_unique<Impl>(device, scene, path);
}

VkProbeTracer::~VkProbeTracer() = default;

void VkProbeTracer::set_options(const probes::UpdateOptions& options) {
  probes::check_update_options(options);
  options_ = options;
}

void VkProbeTracer::scene_posed(const scene::Scene& scene, std::span<const int> moved) {
  Impl& im = *impl_;
  // Deformed meshes that changed pose: their vertices again (in place: the structures keep
  // the buffer's addresses), and their bottom levels.
  const std::vector<std::uint32_t> reshaped = im.layout.repose(scene);
  for (std::uint32_t m : reshaped) {
    const GpuMesh& mesh = im.layout.meshes[m];
    const std::size_t end = m + 1 < im.layout.meshes.size() ? im.layout.meshes[m + 1].first_vertex
                                                             : im.layout.vertices.size();
    gpu::upload(im.device, im.runner, im.vertices, im.layout.vertices.data() + mesh.first_vertex,
                (end - mesh.first_vertex) * sizeof(GpuVertex), VkDeviceSize(mesh.first_vertex) * sizeof(GpuVertex));
  }
  if (!reshaped.empty()) im.acceleration->refit(im.runner, reshaped);
  im.layout.place(scene);
  im.place_buffers();
  if (!moved.empty() || !reshaped.empty()) im.acceleration->update(im.runner, im.layout.instances);
}

const gpu::Buffer& VkProbeTracer::coefficient_buffer() const {
  if (!impl_->coefficients) throw std::logic_error("the GPU probe tracer has not updated a volume yet");
  return *impl_->coefficients;
}

const gpu::Buffer& VkProbeTracer::moment_buffer() const {
  if (!impl_->moments) throw std::logic_error("the GPU probe tracer has not updated a volume yet");
  return *impl_->moments;
}

void VkProbeTracer::defer_host_copy(bool defer) { impl_->defer = defer; }

void VkProbeTracer::read_back(probes::ProbeVolume& volume) const {
  if (impl_->stale.empty()) return;
  if (impl_->mirrored != &volume)
    throw std::logic_error("the GPU probe tracer reads back into the volume it updates");
  impl_->copy_stale(volume);
}

std::size_t VkProbeTracer::stale_probes() const { return impl_->stale.size(); }

std::uint64_t VkProbeTracer::rays_traced() const { return impl_->rays; }

std::vector<Result> VkProbeTracer::Impl::trace(const std::vector<ProbeWork>& items, const std::vector<Blend>& blend_items,
                                               TraceParams tp, ProjectParams pp) {
  const std::uint32_t n = tp.samples;
  std::vector<Result> out;
  out.reserve(items.size());
  // In batches: the projection's work groups (one per probe) and the path buffers are bounded.
  const std::size_t batch = std::clamp<std::size_t>(kMaxBatchPaths / n, 1, kMaxBatchProbes);
  for (std::size_t first = 0; first < items.size(); first += batch) {
    const auto count = static_cast<std::uint32_t>(std::min(batch, items.size() - first));
    ensure(device, work, count * sizeof(ProbeWork), kStorage, gpu::MemoryUse::upload);
    ensure(device, blends, count * sizeof(Blend), kStorage, gpu::MemoryUse::upload);
    ensure(device, paths, VkDeviceSize(count) * n * sizeof(glm::vec4), kStorage, gpu::MemoryUse::device_local);
    ensure(device, distances, VkDeviceSize(count) * n * sizeof(float), kStorage, gpu::MemoryUse::device_local);
    ensure(device, results, count * sizeof(Result), kStorage, gpu::MemoryUse::device_local);
    ensure(device, results_readback, count * sizeof(Result), kStorage, gpu::MemoryUse::readback);
    work->write(items.data() + first, count * sizeof(ProbeWork));
    blends->write(blend_items.data() + first, count * sizeof(Blend));
    write_descriptors();
    tp.work_count = count;
    pp.work_count = count;
    runner.run([&](VkCommandBuffer cmd) {
      // Host writes and earlier submissions (uploads, builds, the last batch) before the trace.
      gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
                          VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT);
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipeline.get());
      vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_RAY_TRACING_KHR, pipeline_layout.get(), 0, 1, &set, 0,
                              nullptr);
      vkCmdPushConstants(cmd, pipeline_layout.get(), VK_SHADER_STAGE_RAYGEN_BIT_KHR, 0, sizeof(tp), &tp);
      rt.cmd_trace_rays(cmd, &raygen_region, &miss_region, &hit_region, &callable_region, n, count, 1);
      gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_RAY_TRACING_SHADER_BIT_KHR, VK_ACCESS_SHADER_WRITE_BIT,
                          VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
      project->bind(cmd);
      project->push(cmd, pp);
      project->dispatch(cmd, count);
      gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                          VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
      gpu::copy_buffer(cmd, *results, *results_readback, count * sizeof(Result));
      gpu::memory_barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                          VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    });
    const std::vector<Result> r = results_readback->read<Result>(count);
    out.insert(out.end(), r.begin(), r.end());
  }
  return out;
}

probes::UpdateStats VkProbeTracer::update(probes::ProbeVolume& volume, std::span<const std::uint32_t> probes) const {
  Impl& im = *impl_;
  const std::vector<std::uint32_t> work = probes::probes_to_update(volume, probes);
  const std::uint32_t n = options_.samples;
  const auto coeffs = static_cast<std::uint32_t>(volume.coefficient_count());
  const VkDeviceSize coefficient_bytes = VkDeviceSize(volume.probe_count()) * coeffs * sizeof(glm::vec3);
  const auto texels = static_cast<std::uint32_t>(volume.moment_texels());
  const VkDeviceSize moment_bytes = VkDeviceSize(volume.probe_count()) * texels * sizeof(glm::vec2);

  // The GPU's running averages follow this volume; another volume, or one changed elsewhere
  // since (a file, the CPU tracer), is copied up whole first.
  const bool in_sync = im.mirrored == &volume && im.mirrored_frame == volume.frame() && im.coefficients &&
                       im.coefficients->size() == coefficient_bytes &&
                       im.mirrored_moment_resolution == volume.moment_resolution();
  // Deferred copies of the volume the GPU mirrored go to it first: the copy up must not
  // overwrite the GPU's newer values with stale ones.
  if (!in_sync && im.mirrored != &volume && !im.stale.empty())
    throw std::logic_error("the GPU probe tracer holds deferred averages of another volume: read_back() first");
  if (!in_sync) {
    if (im.mirrored == &volume && im.coefficients && im.coefficients->size() == coefficient_bytes &&
        im.mirrored_moment_resolution == volume.moment_resolution())
      im.copy_stale(volume);
    im.stale.clear();
  }
  Impl::ensure(im.device, im.coefficients, coefficient_bytes, kStorage, gpu::MemoryUse::device_local);
  Impl::ensure(im.device, im.moments, moment_bytes, kStorage, gpu::MemoryUse::device_local);
  if (!in_sync) {
    const auto all = volume.all_coefficients();
    gpu::upload(im.device, im.runner, *im.coefficients, all.data(), all.size_bytes());
    if (volume.has_moments()) {
      std::vector<glm::vec2> moments;
      moments.reserve(std::size_t(volume.probe_count()) * texels);
      for (std::uint32_t p = 0; p < volume.probe_count(); ++p) {
        const auto m = volume.moments(p);
        moments.insert(moments.end(), m.begin(), m.end());
      }
      gpu::upload(im.device, im.runner, *im.moments, moments.data(), moment_bytes);
    }
  }

  volume.begin_update();
  probes::UpdateStats stats;
  stats.frame = volume.frame();
  stats.probes_traced = static_cast<std::uint32_t>(work.size());
  stats.paths = std::uint64_t(work.size()) * n;
  const auto start = std::chrono::steady_clock::now();

  if (!work.empty()) {
    if (im.lattice_samples != n) {
      std::vector<glm::vec4> lattice(n);
      for (std::uint32_t i = 0; i < n; ++i) lattice[i] = glm::vec4(probes::fibonacci_direction(i, n), 0.0f);
      Impl::ensure(im.device, im.lattice, lattice.size() * sizeof(glm::vec4), kStorage, gpu::MemoryUse::device_local);
      gpu::upload(im.device, im.runner, *im.lattice, lattice.data(), lattice.size() * sizeof(glm::vec4));
      im.lattice_samples = n;
    }
    const TraceParams tp{n,
                         0,
                         fold(options_.seed),
                         fold(stats.frame),
                         im.path.max_bounces,
                         im.path.rr_min_bounces,
                         im.path.indirect_clamp,
                         static_cast<std::uint32_t>(im.layout.lights.size()),
                         static_cast<std::uint32_t>(im.layout.emissive.size()),
                         im.sky.r,
                         im.sky.g,
                         im.sky.b,
                         im.layout.environment};
    const ProjectParams pp{n, static_cast<std::uint32_t>(volume.sh_order()), 0,
                           static_cast<std::uint32_t>(volume.moment_resolution()), volume.moment_range(),
                           static_cast<float>(std::bit_floor(0xFFFFFFFFu / n))};
    // Each probe's rotation from its own stream, as ProbeTracer::trace_probe draws it; its
    // origin where it is now (relocated or not); the blend weight from its history, as
    // ProbeVolume::accumulate computes it.
    const std::uint32_t limit = backface_limit(n, options_.backface_threshold);
    const auto make_work = [&](const std::vector<std::uint32_t>& list, std::vector<ProbeWork>& items,
                               std::vector<Blend>& blends, std::uint32_t flags) {
      items.assign(list.size(), ProbeWork{});
      blends.assign(list.size(), Blend{});
      for (std::size_t w = 0; w < list.size(); ++w) {
        const std::uint32_t p = list[w];
        trace::Sampler sampler(options_.seed, p, stats.frame);
        const glm::mat3 rotation = probes::random_rotation(sampler);
        items[w].origin = glm::vec4(volume.position(p), std::bit_cast<float>(p));
        for (int c = 0; c < 3; ++c) items[w].rotation[c] = glm::vec4(rotation[c], 0.0f);
        const probes::ProbeState& s = volume.state(p);
        const probes::BlendHistory history{s.updates, s.samples, std::max<std::uint32_t>(s.age, 1u)};
        blends[w].probe = p;
        blends[w].weight = probes::blend_weight(options_.blend, history, n, options_.hysteresis,
                                                options_.reference_samples ? options_.reference_samples : n);
        blends[w].backface_limit = s.unclassified() ? limit : ~0u;
        blends[w].flags = flags;
      }
    };
    std::vector<ProbeWork> items;
    std::vector<Blend> blends;

    if (options_.relocate) {
      // Relocation as ProbeTracer does it: a probe being classified first looks around (a dry
      // pass that blends nothing), moves where its nearest hits say (probes::relocated_offset),
      // then the update below traces it from there and classifies it by those rays. A probe
      // that stays traces the same paths again (same streams, same origin), as if kept.
      std::vector<std::uint32_t> fresh;
      for (std::uint32_t p : work)
        if (volume.state(p).unclassified()) fresh.push_back(p);
      if (!fresh.empty()) {
        make_work(fresh, items, blends, kBlendDry);
        const std::vector<Result> looks = im.trace(items, blends, tp, pp);
        for (std::size_t w = 0; w < fresh.size(); ++w) {
          const Result& r = looks[w];
          stats.rays += r.rays;
          const glm::mat3 rotation(glm::vec3(items[w].rotation[0]), glm::vec3(items[w].rotation[1]),
                                   glm::vec3(items[w].rotation[2]));
          const auto direction = [&](std::uint32_t i) {
            return glm::normalize(rotation * probes::fibonacci_direction(i, n));
          };
          probes::NearestHits hits;
          if (r.back_path != ~0u) {
            hits.back = r.nearest_back;
            hits.back_dir = direction(r.back_path);
          }
          if (r.front_path != ~0u) {
            hits.front = r.nearest_front;
            hits.front_dir = direction(r.front_path);
          }
          const bool inside = probes::classify(r.backfaces, n, options_.backface_threshold).inside_geometry;
          const glm::vec3 moved = probes::relocated_offset(volume, fresh[w], hits, inside);
          if (moved != volume.offset(fresh[w])) volume.set_offset(fresh[w], moved);
        }
      }
    }

    make_work(work, items, blends, 0);
    const std::vector<Result> results = im.trace(items, blends, tp, pp);
    // The host volume follows what the GPU did: classification, counts, and the blended
    // averages of the updated probes, copied back now or, deferred, by read_back().
    for (std::size_t w = 0; w < work.size(); ++w) {
      const std::uint32_t p = work[w];
      const Result& r = results[w];
      stats.rays += r.rays;
      stats.invalid_samples += r.invalid;
      probes::ProbeState& state = volume.state(p);
      if (state.unclassified()) {
        const probes::Classification c = probes::classify(r.backfaces, n, options_.backface_threshold);
        state.backface_fraction = c.backface_fraction;
        state.flags = std::uint8_t(state.flags & ~probes::kProbeUnclassified);
        if (c.inside_geometry) {
          volume.deactivate(p, true);
          state.age = 0;
          ++stats.newly_inactive;
          continue;
        }
      }
      state.updates += 1;
      state.samples += n;
      state.age = 0;
      im.stale.push_back(p);
    }
  }
  im.mirrored = &volume;
  im.mirrored_frame = volume.frame();
  im.mirrored_moment_resolution = volume.moment_resolution();
  if (im.defer)
    im.compact_stale();
  else
    im.copy_stale(volume);
  im.rays += stats.rays;
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace ddish::trace_vk
