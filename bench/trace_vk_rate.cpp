// The GPU probe tracer's ray rate beside the Embree one's, on the same probes: the scene's grid
// (as trace_floor places it), S paths per probe, the same bounces; each tracer's first update
// classifies the probes (and builds the GPU pipeline's state), updates 2..K are timed.
//
//   trace_vk_rate SCENE [--grid X,Y,Z] [--samples N] [--bounces N] [--updates K] [--device N]
//                       [--tracers both|vulkan|embree] [--probe-visibility R|both]
//                       [--environment FILE.exr|.hdr [--environment-rotation DEG]
//                        [--environment-intensity K]]
//
// --environment lights the scene with an equirectangular map in place of its uniform sky, as
// `ddish probes --environment` does (both tracers importance-sample it: one more shadow ray per
// bounce). --probe-visibility R gives the volume R x R distance-moment maps (default 8, as
// `ddish render`; 0: none); `both` times volumes without and with 8 x 8 maps, their updates
// interleaved (one without, one with, ...), so the moments' cost is measured under the same load.
// Prints one CSV row per moment resolution (header first) with each tracer's median update time,
// rays per update and Mrays/s, the Vulkan device and the map ("-": none). The two tracers cast different rays (other random numbers), so
// rays per update differ by the Monte Carlo noise of path lengths. Exit 2 when the device has
// no ray-tracing pipelines (with --tracers embree it is not opened).
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_grid.h"
#include "gpu/context.h"
#include "metrics/image_io.h"
#include "probes/moment_map.h"
#include "probes/probe_grid.h"
#include "probes/probe_tracer.h"
#include "probes/probe_volume.h"
#include "probes/tracer_source.h"
#include "scene/gltf_loader.h"
#include "scene/scene.h"
#include "trace/tracer.h"
#include "trace_vk/vk_probe_tracer.h"

namespace {

using namespace ddish;

struct Rate {
  double ms = 0.0;      // median update
  double rays = 0.0;    // median rays per update
  double mrays_s = 0.0; // rays / time over the timed updates
  std::uint32_t probes = 0;
};



// One rate per moment resolution, each on its own volume; the timed updates take the volumes in
// turn.
std::vector<Rate> measure(const probes::ProbeUpdater& updater, const probes::ProbeGrid& grid, int updates,
                          const std::vector<int>& resolutions) {
  std::vector<probes::ProbeVolume> volumes;
  for (int r : resolutions) volumes.emplace_back(grid, probes::kDefaultShOrder, r);
  for (probes::ProbeVolume& v : volumes) updater.update_all(v);  // classification, first-use costs
  const std::size_t n = volumes.size();
  std::vector<std::vector<double>> ms(n), rays(n);
  std::vector<double> total_s(n, 0.0), total_rays(n, 0.0);
  for (int k = 1; k < updates; ++k)
    for (std::size_t i = 0; i < n; ++i) {
      const probes::UpdateStats u = updater.update_all(volumes[i]);
      ms[i].push_back(u.seconds * 1e3);
      rays[i].push_back(double(u.rays));
      total_s[i] += u.seconds;
      total_rays[i] += double(u.rays);
    }
  std::vector<Rate> out;
  for (std::size_t i = 0; i < n; ++i)
    out.push_back({bench::median(ms[i]), bench::median(rays[i]), total_s[i] > 0.0 ? total_rays[i] / total_s[i] * 1e-6 : 0.0,
                   volumes[i].active_count()});
  return out;
}

}  // namespace

int main(int argc, char** argv) try {
  std::string path, grid, tracers = "both", environment, visibility = "8";
  float environment_rotation = 0.0f, environment_intensity = 1.0f;
  int samples = 256, bounces = 15, updates = 4;  // bounces: ddish render's default
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
    else if (a == "--updates") updates = std::stoi(next());
    else if (a == "--device") device = static_cast<std::uint32_t>(std::stoul(next()));
    else if (a == "--tracers") tracers = next();
    else if (a == "--probe-visibility") visibility = next();
    else if (a == "--environment") environment = next();
    else if (a == "--environment-rotation") environment_rotation = std::stof(next());
    else if (a == "--environment-intensity") environment_intensity = std::stof(next());
    else if (!a.empty() && a[0] == '-') throw std::invalid_argument("unknown option " + a);
    else path = a;
  }
  if (path.empty())
    throw std::invalid_argument("usage: trace_vk_rate SCENE [--grid X,Y,Z] [--samples N] [--bounces N] "
                                "[--updates K] [--device N] [--tracers both|vulkan|embree] [--probe-visibility R|both] "
                                "[--environment FILE [--environment-rotation DEG] [--environment-intensity K]]");
  if (samples < 1 || bounces < 0 || updates < 2) throw std::invalid_argument("need --samples >= 1, --bounces >= 0, --updates >= 2");
  if (tracers != "both" && tracers != "vulkan" && tracers != "embree")
    throw std::invalid_argument("--tracers is both, vulkan or embree, got '" + tracers + "'");
  std::vector<int> resolutions;
  if (visibility == "both") {
    resolutions = {0, 8};
  } else {
    resolutions = {std::stoi(visibility)};
    probes::check_moment_resolution(resolutions[0]);
  }

  scene::Scene s = scene::load_scene(path);
  if (!environment.empty()) {
    // In place of the uniform sky, as app/lighting_options.h's apply_lighting does.
    metrics::Image image = metrics::read_image(environment);
    s.environment_map = std::make_shared<const scene::EnvironmentMap>(
        scene::make_environment_map(image.width(), image.height(), std::move(image.pixels()), environment_rotation,
                                    environment_intensity, environment));
    s.sidecar.environment = glm::vec3(0.0f);
  }
  const probes::ProbeGrid grid_used = bench::place_grid(s, grid);
  trace::PathOptions path_options;
  path_options.max_bounces = bounces;
  probes::UpdateOptions options;
  options.samples = static_cast<std::uint32_t>(samples);
  options.seed = 1;

  std::vector<Rate> embree(resolutions.size()), vulkan(resolutions.size());
  std::string device_name = "-";
  if (tracers != "vulkan") {
    const trace::Tracer tracer(s, path_options);
    const probes::TracerSource source(tracer);
    embree = measure(probes::ProbeTracer(source, options), grid_used, updates, resolutions);
  }
  if (tracers != "embree") {
    gpu::Context gpu(gpu::ContextOptions{.device_index = device, .ray_tracing = true});
    device_name = gpu.device().info().name;
    if (!gpu.device().features().ray_tracing) {
      std::fprintf(stderr, "trace_vk_rate: %s has no Vulkan ray-tracing pipelines\n", device_name.c_str());
      return 2;
    }
    const trace_vk::VkProbeTracer tracer(gpu.device(), s, path_options, options);
    vulkan = measure(tracer, grid_used, updates, resolutions);
  }
  std::printf("scene,triangles,probes,active,samples,bounces,moment_resolution,embree_ms,embree_rays,embree_mrays_s,"
              "vulkan_ms,vulkan_rays,vulkan_mrays_s,vulkan_device,environment\n");
  for (std::size_t i = 0; i < resolutions.size(); ++i) {
    const Rate& e = embree[i];
    const Rate& v = vulkan[i];
    std::printf("%s,%zu,%u,%u,%d,%d,%d,%.3f,%.0f,%.3f,%.3f,%.0f,%.3f,\"%s\",\"%s\"\n", s.path.c_str(),
                s.triangle_count(), grid_used.probe_count(), std::max(e.probes, v.probes), samples, bounces,
                resolutions[i], e.ms, e.rays, e.mrays_s, v.ms, v.rays, v.mrays_s, device_name.c_str(),
                environment.empty() ? "-" : environment.c_str());
  }
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "trace_vk_rate: %s\n", e.what());
  return 2;
}
