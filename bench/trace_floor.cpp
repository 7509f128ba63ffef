// The tracing floor of a probe update: the rays a real probe update casts, recorded as it casts
// them (trace/ray_recorder.h: probe and bounce rays as closest-hit queries, shadow rays as
// occlusion queries, same directions, same proportions, each thread's rays in path order), then
// replayed with plain rtcIntersect1 / rtcOccluded1 on one flat Embree scene of the world-space
// triangles (no instancing level, no filter functions, no shading) over the same threads. The
// full probe update (probes::ProbeTracer with the path tracer) of the same probes, seed and
// update number casts exactly those rays, so update Mrays/s ÷ floor Mrays/s is the share of
// Embree's raw speed the update reaches.
//
// A second replay goes through the tracer's own Embree scene as the tracer calls it
// (trace::EmbreeScene: per-mesh BVHs under an instance level, alpha-test filters): what the
// update would cost if shading were free.
//
// Which floor the share is of: the first replay's scene has Embree's default settings
// (RTC_SCENE_FLAG_NONE, so not robust; RTC_BUILD_QUALITY_MEDIUM). The tracer's own scene is
// RTC_SCENE_FLAG_ROBUST (the watertight test leaks without it) and RTC_BUILD_QUALITY_HIGH, with
// filter callbacks on alpha-tested materials; its replay (the scene_floor_* columns) is the
// floor the update could reach with free shading. update_share_of_floor* is of the first.
//
//   trace_floor SCENE [--grid X,Y,Z] [--samples N] [--bounces N] [--updates K] [--repeat R]
//                     [--threads T] [--stream G1,G2,...]
//
// Grid: --grid counts over the sidecar's probe bounds (else the scene's bounds); without it the
// sidecar's counts; without those the automatic grid (what `ddish render` places by default).
// The first update classifies the probes (those found inside geometry are left out from then on);
// updates 2..K are timed. Before each, the same update runs once on a copy of the volume with
// the recorder on (untimed), and its rays are replayed R times. Threads: TBB's default (all
// cores), or T. Prints one CSV row (header first): the update with the median time, and the
// medians of its floor's repeats; the *_cpu columns are process CPU time (all threads) instead
// of wall-clock time.
//
// --stream: the same rays also through Embree's stream API (rtcIntersect1M / rtcOccluded1M, the
// queries a batched integrator would make), in groups of G consecutive rays of each kind per
// thread, once with the incoherent and once with the coherent context flag (coherent: Embree
// sorts each group into packets by direction octant). One comment line ('#') per group size and
// flag and timed update, after the floor's own R repeats: median ms beside the floor's, and the
// hit counts (the same unless a packet and a single ray disagree on an edge).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <sys/resource.h>

#include <embree3/rtcore.h>
#include <glm/glm.hpp>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "bench_grid.h"
#include "probes/probe_grid.h"
#include "probes/probe_tracer.h"
#include "probes/probe_volume.h"
#include "probes/tracer_source.h"
#include "scene/gltf_loader.h"
#include "scene/scene.h"
#include "trace/embree_scene.h"
#include "trace/ray_recorder.h"
#include "trace/tracer.h"

namespace {

using namespace ddish;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// CPU seconds of the whole process (all threads, user + system): under a loaded machine the
// update's and the floor's CPU times compare more steadily than their wall-clock times.
double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  auto s = [](const timeval& t) { return double(t.tv_sec) + 1e-6 * double(t.tv_usec); };
  return s(u.ru_utime) + s(u.ru_stime);
}




// An Embree occlusion ray for a recorded shadow ray (full mask, id, flags and time 0).
RTCRay to_rtc_ray(const trace::RecordedRay& r) {
  RTCRay ray{};
  ray.org_x = r.origin.x;
  ray.org_y = r.origin.y;
  ray.org_z = r.origin.z;
  ray.dir_x = r.direction.x;
  ray.dir_y = r.direction.y;
  ray.dir_z = r.direction.z;
  ray.tnear = r.tmin;
  ray.tfar = r.tmax;
  ray.mask = 0xFFFFFFFFu;
  return ray;
}

// One flat Embree scene of every instance's triangles in world space: the cheapest closest-hit
// structure Embree offers for these rays (no instancing level, no filter callbacks; Embree's
// default scene flags and build quality: not robust, MEDIUM).
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

  // Every ray in parallel, closest-hit or occlusion query as recorded; returns the number of
  // rays that hit something.
  std::uint64_t trace(const std::vector<trace::RecordedRay>& rays) const {
    std::atomic<std::uint64_t> hits{0};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 1024),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        RTCIntersectContext context;
                        rtcInitIntersectContext(&context);
                        std::uint64_t local = 0;
                        for (std::size_t i = range.begin(); i != range.end(); ++i) {
                          const trace::RecordedRay& r = rays[i];
                          if (r.occlusion) {
                            RTCRay ray = to_rtc_ray(r);
                            rtcOccluded1(scene_, &context, &ray);
                            if (ray.tfar < 0.0f) ++local;
                          } else {
                            const trace::Ray ray{r.origin, r.direction, r.tmin, r.tmax, 0.0f};
                            RTCRayHit rh = trace::to_rtc_rayhit(ray);
                            rtcIntersect1(scene_, &context, &rh);
                            if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) ++local;
                          }
                        }
                        hits += local;
                      });
    return hits.load();
  }

  // The same rays through rtcIntersect1M / rtcOccluded1M, `group` consecutive rays of each kind
  // at a time per thread; returns the number of rays that hit something (the same as trace()).
  std::uint64_t trace_stream(const std::vector<trace::RecordedRay>& rays, std::size_t group,
                             bool coherent) const {
    std::atomic<std::uint64_t> hits{0};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 1024),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        RTCIntersectContext context;
                        rtcInitIntersectContext(&context);
                        context.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT
                                                 : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
                        std::vector<RTCRayHit> closest;
                        std::vector<RTCRay> shadow;
                        closest.reserve(group);
                        shadow.reserve(group);
                        std::uint64_t local = 0;
                        auto flush = [&]() {
                          if (!closest.empty()) {
                            rtcIntersect1M(scene_, &context, closest.data(), unsigned(closest.size()),
                                           sizeof(RTCRayHit));
                            for (const RTCRayHit& h : closest) local += h.hit.geomID != RTC_INVALID_GEOMETRY_ID;
                            closest.clear();
                          }
                          if (!shadow.empty()) {
                            rtcOccluded1M(scene_, &context, shadow.data(), unsigned(shadow.size()), sizeof(RTCRay));
                            for (const RTCRay& r : shadow) local += r.tfar < 0.0f;
                            shadow.clear();
                          }
                        };
                        for (std::size_t i = range.begin(); i != range.end(); ++i) {
                          const trace::RecordedRay& r = rays[i];
                          if (r.occlusion) {
                            shadow.push_back(to_rtc_ray(r));
                          } else {
                            closest.push_back(trace::to_rtc_rayhit(trace::Ray{r.origin, r.direction, r.tmin, r.tmax, 0.0f}));
                          }
                          if (closest.size() >= group || shadow.size() >= group) flush();
                        }
                        flush();
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

// The same rays through the tracer's own Embree scene, as trace_path casts them.
std::uint64_t trace_on(const trace::EmbreeScene& scene, const std::vector<trace::RecordedRay>& rays) {
  std::atomic<std::uint64_t> hits{0};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      std::uint64_t local = 0;
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        const trace::RecordedRay& r = rays[i];
                        const trace::RayQuery query{r.alpha_seed, r.cone_width, r.cone_spread, -1};
                        if (r.occlusion) {
                          if (scene.occluded(r.origin, r.direction, r.tmin, r.tmax, query)) ++local;
                        } else {
                          trace::Hit hit;
                          const trace::Ray ray{r.origin, r.direction, r.tmin, r.tmax, 0.0f};
                          if (scene.intersect(ray, query, hit)) ++local;
                        }
                      }
                      hits += local;
                    });
  return hits.load();
}

}  // namespace

int main(int argc, char** argv) try {
  std::string path, grid, stream_list;
  int samples = 256, bounces = 15, updates = 4, repeat = 3, threads = 0;  // bounces: ddish render's default
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
    else if (a == "--threads") threads = std::stoi(next());
    else if (a == "--stream") stream_list = next();
    else if (!a.empty() && a[0] == '-') throw std::invalid_argument("unknown option " + a);
    else path = a;
  }
  if (path.empty())
    throw std::invalid_argument("usage: trace_floor SCENE [--grid X,Y,Z] [--samples N] [--bounces N] "
                                "[--updates K] [--repeat R] [--threads T] [--stream G1,G2,...]");
  if (samples < 1 || bounces < 0 || updates < 2 || repeat < 1 || threads < 0)
    throw std::invalid_argument("need --samples >= 1, --bounces >= 0, --updates >= 2, --repeat >= 1, --threads >= 0");
  std::vector<std::size_t> stream_groups;
  for (std::size_t at = 0; at < stream_list.size();) {
    const std::size_t comma = std::min(stream_list.find(',', at), stream_list.size());
    const int g = std::stoi(stream_list.substr(at, comma - at));
    if (g < 1) throw std::invalid_argument("--stream group sizes must be >= 1");
    stream_groups.push_back(std::size_t(g));
    at = comma + 1;
  }
  std::optional<tbb::global_control> thread_limit;
  if (threads > 0) thread_limit.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  const int used_threads = threads > 0 ? threads : tbb::this_task_arena::max_concurrency();

  const scene::Scene s = scene::load_scene(path);
  const probes::ProbeGrid probe_grid = bench::place_grid(s, grid);
  trace::PathOptions path_options;
  path_options.max_bounces = bounces;
  trace::Tracer tracer(s, path_options);
  const FlatScene flat(s);

  probes::ProbeVolume volume(probe_grid, probes::kDefaultShOrder);
  const probes::TracerSource source(tracer);
  probes::UpdateOptions options;
  options.samples = static_cast<std::uint32_t>(samples);
  options.seed = 1;
  const probes::ProbeTracer probe_tracer(source, options);
  probe_tracer.update(volume);  // classification: probes inside geometry are left out afterwards

  // Per timed update: seconds, rays and paths of the update; medians over the repeats of its floors.
  std::vector<double> update_s, update_rays_v, update_paths, floor_s, scene_floor_s, update_cpu, floor_cpu,
      scene_floor_cpu;
  std::vector<std::uint64_t> hits_v, shadow_v;
  trace::RayRecorder recorder;
  for (int k = 1; k < updates; ++k) {
    // The update about to run, once on a copy of the volume with the recorder on: the same
    // probes, seed and update number cast the same rays.
    probes::ProbeVolume copy = volume;
    tracer.set_ray_recorder(&recorder);
    probe_tracer.update(copy);
    tracer.set_ray_recorder(nullptr);
    const std::vector<trace::RecordedRay> rays = recorder.take();
    std::vector<double> flat_s, scene_s, flat_cpu, scene_cpu;
    std::uint64_t floor_hits = 0;
    for (int r = 0; r < repeat; ++r) {
      Clock::time_point t0 = Clock::now();
      const double c0 = cpu_seconds();
      floor_hits = flat.trace(rays);
      flat_s.push_back(seconds_since(t0));
      flat_cpu.push_back(cpu_seconds() - c0);
      t0 = Clock::now();
      const double c1 = cpu_seconds();
      trace_on(tracer.embree_scene(), rays);
      scene_s.push_back(seconds_since(t0));
      scene_cpu.push_back(cpu_seconds() - c1);
    }
    for (const std::size_t g : stream_groups) {
      for (const bool coherent : {false, true}) {
        std::vector<double> st;
        std::uint64_t stream_hits = 0;
        for (int r = 0; r < repeat; ++r) {
          const Clock::time_point t0 = Clock::now();
          stream_hits = flat.trace_stream(rays, g, coherent);
          st.push_back(seconds_since(t0));
        }
        std::printf("# update %d stream group %zu %s: %.3f ms, floor %.3f ms (%.3f x); %llu hits, floor %llu\n", k,
                    g, coherent ? "coherent" : "incoherent", bench::median(st) * 1e3, bench::median(flat_s) * 1e3,
                    bench::median(st) / bench::median(flat_s), static_cast<unsigned long long>(stream_hits),
                    static_cast<unsigned long long>(floor_hits));
      }
    }
    floor_s.push_back(bench::median(flat_s));
    floor_cpu.push_back(bench::median(flat_cpu));
    scene_floor_cpu.push_back(bench::median(scene_cpu));
    scene_floor_s.push_back(bench::median(scene_s));
    hits_v.push_back(floor_hits);
    shadow_v.push_back(std::uint64_t(std::count_if(rays.begin(), rays.end(),
                                              [](const trace::RecordedRay& r) { return r.occlusion; })));
    const double c0 = cpu_seconds();
    const probes::UpdateStats u = probe_tracer.update(volume);
    update_cpu.push_back(cpu_seconds() - c0);
    update_s.push_back(u.seconds);
    update_rays_v.push_back(double(u.rays));
    update_paths.push_back(double(u.paths));
    if (u.rays != rays.size())
      throw std::runtime_error("the update cast " + std::to_string(u.rays) + " rays, the recording has " +
                               std::to_string(rays.size()));
  }
  // The update with the median time, and its own floors: one update's rays throughout.
  std::vector<std::size_t> order(update_s.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return update_s[a] < update_s[b]; });
  const std::size_t m = order[order.size() / 2];
  const double fs = floor_s[m], ss = scene_floor_s[m], us = update_s[m];
  const double ur = update_rays_v[m], up = update_paths[m];
  const auto floor_rays = static_cast<std::uint64_t>(ur);
  const std::uint64_t floor_hits = hits_v[m], shadow_rays = shadow_v[m];
  const double floor_mrays = fs > 0 ? ur / fs * 1e-6 : 0.0;
  const double update_mrays = us > 0 ? ur / us * 1e-6 : 0.0;
  std::printf("scene,triangles,grid,probes,active,samples,bounces,threads,floor_rays,floor_shadow_rays,"
              "floor_hit_fraction,floor_ms,floor_mrays_s,scene_floor_ms,scene_floor_mrays_s,update_ms,"
              "update_paths,update_rays,update_mrays_s,update_primary_mrays_s,update_over_floor,"
              "update_share_of_floor,floor_mrays_s_per_thread,update_mrays_s_per_thread,floor_cpu_ms,update_cpu_ms,"
              "update_share_of_floor_cpu,scene_floor_cpu_ms,tracer_scene\n");
  std::printf("%s,%zu,%dx%dx%d,%u,%u,%d,%d,%d,%llu,%llu,%.4f,%.3f,%.3f,%.3f,%.3f,%.3f,%.0f,%.0f,%.3f,%.3f,%.2f,%.3f,"
              "%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%s\n",
              path.c_str(), flat.triangles(), probe_grid.counts().x, probe_grid.counts().y,
              probe_grid.counts().z, probe_grid.probe_count(), volume.active_count(), samples, bounces,
              used_threads, static_cast<unsigned long long>(floor_rays),
              static_cast<unsigned long long>(shadow_rays),
              floor_rays ? double(floor_hits) / double(floor_rays) : 0.0, fs * 1e3, floor_mrays, ss * 1e3,
              ss > 0 ? double(floor_rays) / ss * 1e-6 : 0.0, us * 1e3, up, ur, update_mrays,
              us > 0 ? up / us * 1e-6 : 0.0, fs > 0 ? us / fs : 0.0,
              floor_mrays > 0 ? update_mrays / floor_mrays : 0.0, floor_mrays / used_threads,
              update_mrays / used_threads, floor_cpu[m] * 1e3, update_cpu[m] * 1e3,
              update_cpu[m] > 0 ? floor_cpu[m] / update_cpu[m] : 0.0, scene_floor_cpu[m] * 1e3,
              tracer.embree_scene().flat() ? "flat" : "instanced");
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "trace_floor: %s\n", e.what());
  return 1;
}
