// What the GPU-resident probe hand-off saves per frame (issue 17, DESIGN.md "GPU probe tracing"):
// the Vulkan tracer and the rasterizer on one device, the tracer's averages left on the GPU
// (VkProbeTracer::defer_host_copy). After each probe update, the same probes go to the same
// renderer both ways: the hand-off (Renderer::import_probes: the conversion on the device, its
// submission and wait) and the read-back path (VkProbeTracer::read_back, the copy every update
// makes without the hand-off, then Renderer::upload_probes: packing on the CPU, staging, copies,
// wait). Both leave the same bits in the textures, so the order does not matter to what is drawn.
//
//   probe_handoff SCENE [--grid X,Y,Z] [--samples N] [--bounces N] [--rounds K] [--fraction F]
//                       [--probe-visibility R] [--device N]
//
// --fraction F: each update traces that share of the active probes (a sliding window, so every
// probe comes round), 1 by default (`ddish render` without a budget traces them all). Rounds
// 2..K are timed (the first classifies). Prints one CSV row: medians of read-back, upload and
// import milliseconds and the saving (read-back + upload - import) per update.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_grid.h"
#include "gpu/context.h"
#include "probes/moment_map.h"
#include "probes/probe_tracer.h"
#include "probes/probe_volume.h"
#include "raster/renderer.h"
#include "scene/gltf_loader.h"
#include "scene/scene.h"
#include "trace/tracer.h"
#include "trace_vk/vk_probe_tracer.h"

namespace {

using namespace ddish;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

}  // namespace

int main(int argc, char** argv) try {
  std::string path, grid;
  int samples = 64, bounces = 2, rounds = 6, visibility = 8;
  double fraction = 1.0;
  std::optional<std::uint32_t> device;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    if (a == "--grid") grid = next();
    else if (a == "--samples") samples = std::stoi(next());
    else if (a == "--bounces") bounces = std::stoi(next());
    else if (a == "--rounds") rounds = std::stoi(next());
    else if (a == "--fraction") fraction = std::stod(next());
    else if (a == "--probe-visibility") visibility = std::stoi(next());
    else if (a == "--device") device = static_cast<std::uint32_t>(std::stoul(next()));
    else if (!a.empty() && a[0] == '-') throw std::invalid_argument("unknown option " + a);
    else path = a;
  }
  if (path.empty())
    throw std::invalid_argument("usage: probe_handoff SCENE [--grid X,Y,Z] [--samples N] [--bounces N] [--rounds K] "
                                "[--fraction F] [--probe-visibility R] [--device N]");
  if (samples < 1 || bounces < 0 || rounds < 2 || !(fraction > 0.0 && fraction <= 1.0))
    throw std::invalid_argument("need --samples >= 1, --bounces >= 0, --rounds >= 2, 0 < --fraction <= 1");
  probes::check_moment_resolution(visibility);

  scene::Scene s = scene::load_scene(path);
  s.pose(0.0);
  const probes::ProbeGrid grid_used = bench::place_grid(s, grid);
  trace::PathOptions path_options;
  path_options.max_bounces = bounces;
  probes::UpdateOptions options;
  options.samples = static_cast<std::uint32_t>(samples);
  options.seed = 1;

  gpu::Context gpu(gpu::ContextOptions{.device_index = device, .ray_tracing = true});
  if (!gpu.device().features().ray_tracing) {
    std::fprintf(stderr, "probe_handoff: %s has no Vulkan ray-tracing pipelines\n", gpu.device().info().name.c_str());
    return 2;
  }
  probes::ProbeVolume volume(grid_used, probes::kDefaultShOrder, visibility);
  trace_vk::VkProbeTracer tracer(gpu.device(), s, path_options, options);
  tracer.defer_host_copy(true);
  raster::Renderer renderer(gpu.device(), s, volume);

  std::vector<double> readback_ms, upload_ms, import_ms;
  std::size_t start = 0, updated = 0;
  for (int k = 0; k < rounds; ++k) {
    std::vector<std::uint32_t> active;
    for (std::uint32_t p = 0; p < volume.probe_count(); ++p)
      if (volume.state(p).active()) active.push_back(p);
    if (active.empty()) throw std::runtime_error("no active probe");
    const auto n = std::max<std::size_t>(1, std::size_t(fraction * double(active.size()) + 0.5));
    std::vector<std::uint32_t> list;
    for (std::size_t i = 0; i < n; ++i) list.push_back(active[(start + i) % active.size()]);
    start = (start + n) % active.size();
    std::sort(list.begin(), list.end());
    tracer.update(volume, list);
    // What changed: the probes traced (a probe found inside geometry too: weight 0 now).
    auto t = Clock::now();
    renderer.import_probes(volume, {&tracer.coefficient_buffer(), &tracer.moment_buffer()}, list);
    const double imported = ms_since(t);
    t = Clock::now();
    tracer.read_back(volume);
    const double read = ms_since(t);
    t = Clock::now();
    renderer.upload_probes(volume, list);
    const double uploaded = ms_since(t);
    if (k == 0) continue;
    import_ms.push_back(imported);
    readback_ms.push_back(read);
    upload_ms.push_back(uploaded);
    updated = list.size();
  }
  const double r = bench::median(readback_ms), u = bench::median(upload_ms), i = bench::median(import_ms);
  std::printf("scene,probes,active,updated,moment_resolution,readback_ms,upload_ms,import_ms,saved_ms,device\n");
  std::printf("%s,%u,%u,%zu,%d,%.3f,%.3f,%.3f,%.3f,\"%s\"\n", s.path.c_str(), grid_used.probe_count(),
              volume.active_count(), updated, visibility, r, u, i, r + u - i, gpu.device().info().name.c_str());
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "probe_handoff: %s\n", e.what());
  return 2;
}
