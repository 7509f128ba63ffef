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
#include "trace_vk/vk_probe_tracer_impl.h"

namespace ddish::trace_vk {

namespace {

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
