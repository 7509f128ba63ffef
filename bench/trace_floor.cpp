// The tracing floor of a probe update: the rays a probe update starts (the randomly rotated
// spherical Fibonacci directions from every active probe of the scene's grid, probes/fibonacci.h)
// traced as plain closest-hit queries, rtcIntersect1 on one flat Embree scene of the world-space
// triangles, with no filter functions, no shading and no bounces; against the full probe update
// (probes::ProbeTracer with the path tracer) of the same probes and samples.
//
//   trace_floor SCENE [--grid X,Y,Z] [--samples N] [--bounces N] [--updates K] [--repeat R]
//
// Grid: --grid counts over the sidecar's probe bounds (else the scene's bounds); without it the
// sidecar's counts; without those the automatic grid (what `ddish render` places by default).
// The first update classifies the probes (those found inside geometry are left out from then on);
// updates 2..K are timed, and the floor traces the rays of each of those updates R times.
// Prints one CSV row (header first) with medians; threads are TBB's default (all cores).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/glm.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "probes/fibonacci.h"
#include "probes/probe_grid.h"
#include "probes/probe_tracer.h"
#include "probes/probe_volume.h"
#include "probes/tracer_source.h"
#include "scene/gltf_loader.h"
#include "scene/scene.h"
#include "trace/embree_scene.h"
#include "trace/sampler.h"
#include "trace/tracer.h"

namespace {

using namespace ddish;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

glm::ivec3 parse_grid(const std::string& text) {
  glm::ivec3 c{0};
  if (std::sscanf(text.c_str(), "%d,%d,%d", &c.x, &c.y, &c.z) != 3 || c.x < 1 || c.y < 1 || c.z < 1)
    throw std::invalid_argument("--grid needs three positive counts X,Y,Z, got '" + text + "'");
  return c;
}

probes::ProbeGrid place(const scene::Scene& s, const std::string& grid) {
  const scene::Aabb bounds = s.sidecar.probe_bounds ? *s.sidecar.probe_bounds : s.bounds();
  if (!grid.empty()) return probes::ProbeGrid(bounds, parse_grid(grid));
  if (s.sidecar.probe_counts) return probes::ProbeGrid(bounds, *s.sidecar.probe_counts);
  return probes::ProbeGrid::fit_auto(bounds);
}

// One flat Embree scene of every instance's triangles in world space: the cheapest closest-hit
// structure Embree offers for these rays (no instancing level, no filter callbacks).
class FlatScene {
 public:
  explicit FlatScene(const scene::Scene& s) {
    device_ = rtcNewDevice(nullptr);
    if (!device_) throw std::runtime_error("rtcNewDevice failed");
    scene_ = rtcNewScene(device_);
    for (const scene::Instance& inst : s.instances) {
      if (inst.mesh < 0) continue;
      const scene::Mesh& mesh = s.meshes[static_cast<std::size_t>(inst.mesh)];
      if (mesh.triangle_count() == 0) continue;
      RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
      auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
          geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float),
          mesh.positions.size()));
      for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const glm::vec3 p = glm::vec3(inst.transform * glm::vec4(mesh.positions[i], 1.0f));
        vertices[3 * i + 0] = p.x;
        vertices[3 * i + 1] = p.y;
        vertices[3 * i + 2] = p.z;
      }
      auto* indices = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(
          geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t),
          mesh.triangle_count()));
      std::copy(mesh.indices.begin(), mesh.indices.end(), indices);
      rtcCommitGeometry(geom);
      rtcAttachGeometry(scene_, geom);
      rtcReleaseGeometry(geom);
      triangles_ += mesh.triangle_count();
    }
    rtcCommitScene(scene_);
    if (rtcGetDeviceError(device_) != RTC_ERROR_NONE)
      throw std::runtime_error("Embree failed to build the flat scene");
  }
  ~FlatScene() {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }
  FlatScene(const FlatScene&) = delete;
  FlatScene& operator=(const FlatScene&) = delete;

  // Closest hit of every ray, in parallel; returns the number of rays that hit something.
  std::uint64_t trace(const std::vector<trace::Ray>& rays) const {
    std::atomic<std::uint64_t> hits{0};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 1024),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        RTCIntersectContext context;
                        rtcInitIntersectContext(&context);
                        std::uint64_t local = 0;
                        for (std::size_t i = range.begin(); i != range.end(); ++i) {
                          RTCRayHit rh = trace::to_rtc_rayhit(rays[i]);
                          rtcIntersect1(scene_, &context, &rh);
                          if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) ++local;
                        }
                        hits += local;
                      });
    return hits.load();
  }

  std::size_t triangles() const { return triangles_; }

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  std::size_t triangles_ = 0;
};

// The primary rays of one probe update (volume update number `frame`), exactly as
// ProbeTracer::trace_probe draws them: the probe's own sampler stream, one random rotation,
// the rotated Fibonacci lattice.
std::vector<trace::Ray> update_rays(const probes::ProbeVolume& volume, std::uint32_t samples,
                                    std::uint64_t seed, std::uint64_t frame) {
  std::vector<trace::Ray> rays;
  for (std::uint32_t p = 0; p < volume.probe_count(); ++p) {
    if (!volume.state(p).active()) continue;
    trace::Sampler sampler(seed, p, frame);
    const glm::mat3 rotation = probes::random_rotation(sampler);
    const glm::vec3 origin = volume.grid().position(p);
    for (std::uint32_t i = 0; i < samples; ++i) {
      trace::Ray ray;
      ray.origin = origin;
      ray.direction = glm::normalize(rotation * probes::fibonacci_direction(i, samples));
      rays.push_back(ray);
    }
  }
  return rays;
}

}  // namespace

int main(int argc, char** argv) try {
  std::string path, grid;
  int samples = 256, bounces = 15, updates = 4, repeat = 3;  // bounces: ddish render's default
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
    else if (a == "--repeat") repeat = std::stoi(next());
    else if (!a.empty() && a[0] == '-') throw std::invalid_argument("unknown option " + a);
    else path = a;
  }
  if (path.empty()) throw std::invalid_argument("usage: trace_floor SCENE [--grid X,Y,Z] [--samples N] [--bounces N] [--updates K] [--repeat R]");
  if (samples < 1 || bounces < 0 || updates < 2 || repeat < 1)
    throw std::invalid_argument("need --samples >= 1, --bounces >= 0, --updates >= 2, --repeat >= 1");

  const scene::Scene s = scene::load_scene(path);
  const probes::ProbeGrid probe_grid = place(s, grid);
  trace::PathOptions path_options;
  path_options.max_bounces = bounces;
  const trace::Tracer tracer(s, path_options);
  const FlatScene flat(s);

  probes::ProbeVolume volume(probe_grid, probes::kDefaultShOrder);
  const probes::TracerSource source(tracer);
  probes::UpdateOptions options;
  options.samples = static_cast<std::uint32_t>(samples);
  options.seed = 1;
  const probes::ProbeTracer probe_tracer(source, options);
  probe_tracer.update(volume);  // classification: probes inside geometry are left out afterwards

  std::vector<double> update_s, update_rays_v, update_paths, floor_s;
  std::uint64_t floor_rays = 0, floor_hits = 0;
  for (int k = 1; k < updates; ++k) {
    // The rays of the update about to run: begin_update() numbers it frame() + 1.
    const std::vector<trace::Ray> rays =
        update_rays(volume, options.samples, options.seed, volume.frame() + 1);
    for (int r = 0; r < repeat; ++r) {
      const Clock::time_point t0 = Clock::now();
      floor_hits = flat.trace(rays);
      floor_s.push_back(seconds_since(t0));
    }
    floor_rays = rays.size();
    const probes::UpdateStats u = probe_tracer.update(volume);
    update_s.push_back(u.seconds);
    update_rays_v.push_back(double(u.rays));
    update_paths.push_back(double(u.paths));
    if (u.paths != rays.size())
      throw std::runtime_error("the update started " + std::to_string(u.paths) +
                               " paths, the floor traced " + std::to_string(rays.size()) + " rays");
  }
  const double fs = median(floor_s), us = median(update_s);
  const double ur = median(update_rays_v), up = median(update_paths);
  std::printf("scene,triangles,grid,probes,active,samples,bounces,threads,floor_rays,floor_hit_fraction,"
              "floor_ms,floor_mrays_s,update_ms,update_paths,update_rays,update_mrays_s,"
              "update_primary_mrays_s,update_over_floor\n");
  std::printf("%s,%zu,%dx%dx%d,%u,%u,%d,%d,%d,%llu,%.4f,%.3f,%.3f,%.3f,%.0f,%.0f,%.3f,%.3f,%.2f\n",
              path.c_str(), flat.triangles(), probe_grid.counts().x, probe_grid.counts().y,
              probe_grid.counts().z, probe_grid.probe_count(), volume.active_count(), samples,
              bounces, tbb::this_task_arena::max_concurrency(),
              static_cast<unsigned long long>(floor_rays),
              floor_rays ? double(floor_hits) / double(floor_rays) : 0.0, fs * 1e3,
              fs > 0 ? double(floor_rays) / fs * 1e-6 : 0.0, us * 1e3, up, ur,
              us > 0 ? ur / us * 1e-6 : 0.0, us > 0 ? up / us * 1e-6 : 0.0, fs > 0 ? us / fs : 0.0);
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "trace_floor: %s\n", e.what());
  return 1;
}
