// The integrator: a unidirectional path tracer with next-event estimation.
//
// - Bounces: max_bounces counts scattering events. 0 returns only what the first ray sees
//   (emission, environment); 1 adds direct lighting of the first hit; and so on.
// - Emission found at the first hit is counted fully (probes must contain emitters). Later, an
//   emitter hit by a BSDF-sampled ray is weighted by the power heuristic against the density
//   with which next-event estimation would have picked the same point.
// - Punctual lights are deltas: next-event estimation only. The uniform environment is reached
//   by BSDF sampling only (no MIS: a uniform radiance gains nothing from light sampling).
//   An environment map (--environment) is importance-sampled (trace/environment_light.h): one
//   next-event sample per scattering, weighted by the power heuristic against BSDF sampling,
//   and an escaping BSDF-sampled ray is weighted the other way (the camera's own ray fully).
// - A back face of a single-sided surface is the inside of a closed object: it absorbs (and is
//   reported, for probe classification).
// - Indirect clamping applies to contributions that scattered at least twice.
// - Russian roulette from rr_min_bounces on: survival = the throughput's largest channel,
//   clamped to [0.05, 1], and the throughput is divided by it (unbiased).
// - Ray cones for mip selection: the width grows by spread × distance; a scattering event of
//   density p stands for about 1/p steradians, so it widens the spread by min(1, 1/sqrt(p)).
#include "trace/tracer.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "scene/scene.h"
#include "trace/bsdf.h"
#include "trace/cpu_dispatch.h"
#include "trace/embree_scene.h"
#include "trace/environment_light.h"
#include "trace/lights.h"
#include "trace/specular_albedo.h"
#include "trace/surface.h"
#include "trace/texture_lookup.h"

namespace ddish::trace {

struct Tracer::Impl {
  Impl(const scene::Scene& s, const PathOptions& o)
      : scene(&s), textures(s), embree(s, textures), lights(s, textures), options(o) {
    if (s.environment_map) environment.emplace(s.environment_map);
    // The BSDF's layer-albedo table (~0.1-0.2 s of quadrature) is built here rather than inside
    // the first path, where it would land in the first probe update's or reference pass's time.
    DielectricSpecularAlbedo::get();
  }

  const scene::Scene* scene;
  TextureSet textures;
  EmbreeScene embree;
  LightSet lights;
  std::optional<EnvironmentLight> environment;  // the scene's map, when it has one
  PathOptions options;
  mutable std::atomic<std::uint64_t> rays{0};
  mutable std::atomic<std::uint64_t> invalid{0};
};

namespace {

float max_component(const glm::vec3& v) { return std::max(v.x, std::max(v.y, v.z)); }

float power_heuristic(float a, float b) {
  const float a2 = a * a;
  const float b2 = b * b;
  return a2 + b2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
}

bool valid_radiance(const glm::vec3& v) {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(v[i]) || v[i] < 0.0f) return false;
  }
  return true;
}

}  // namespace

Tracer::Tracer(const scene::Scene& scene, const PathOptions& options)
    : impl_(std::make_unique<Impl>(scene, options)) {}

Tracer::~Tracer() = default;

void Tracer::update(const scene::Scene& scene, std::span<const int> moved_instances) {
  impl_->scene = &scene;
  impl_->embree.update(scene, moved_instances);
  impl_->lights.update(scene, moved_instances);
}

const PathOptions& Tracer::options() const { return impl_->options; }
void Tracer::set_options(const PathOptions& options) { impl_->options = options; }
std::uint64_t Tracer::rays_traced() const { return impl_->rays.load(std::memory_order_relaxed); }
void Tracer::reset_ray_count() { impl_->rays.store(0, std::memory_order_relaxed); }
void Tracer::set_ray_recorder(RayRecorder* recorder) { impl_->embree.set_recorder(recorder); }
const EmbreeScene& Tracer::embree_scene() const { return impl_->embree; }
std::uint64_t Tracer::invalid_paths() const { return impl_->invalid.load(std::memory_order_relaxed); }

DDISH_CPU_DISPATCH
PathSample Tracer::trace_path(const Ray& primary, Sampler& sampler) const {
  const Impl& im = *impl_;
  const scene::Scene& scene = *im.scene;
  const PathOptions& opt = im.options;
  PathSample out;
  glm::vec3 radiance(0.0f);
  glm::vec3 beta(1.0f);
  std::uint64_t rays = 0;

  // scatterings: how many scattering events the light went through before reaching the origin.
  auto add = [&](glm::vec3 c, int scatterings) {
    if (opt.indirect_clamp > 0.0f && scatterings >= 2) {
      const float m = max_component(c);
      if (m > opt.indirect_clamp) c *= opt.indirect_clamp / m;
    }
    radiance += c;
  };

  Ray ray = primary;
  float cone_width = 0.0f;
  float spread = std::max(primary.cone_spread, 0.0f);
  float prev_bsdf_pdf = 0.0f;

  for (int depth = 0;; ++depth) {
    RayQuery query{sampler.next_u32(), cone_width, spread, opt.fixed_mip_level};
    Hit hit;
    ++rays;
    if (!im.embree.intersect(ray, query, hit)) {
      glm::vec3 sky = scene.environment();
      if (im.environment) {
        const float w =
            depth > 0 ? power_heuristic(prev_bsdf_pdf, im.environment->pdf(ray.direction)) : 1.0f;
        sky += im.environment->radiance(ray.direction) * w;
      }
      add(beta * sky, depth);
      break;
    }
    cone_width += spread * hit.t;
    const int mesh_index = scene.instances[static_cast<std::size_t>(hit.instance)].mesh;
    const scene::Mesh& mesh = scene.meshes[static_cast<std::size_t>(mesh_index)];
    HitInput in;
    in.mesh = &mesh;
    in.triangle = &im.embree.triangle(mesh_index, hit.prim);
    in.material = &scene.material_of(mesh);
    in.transform = &im.embree.transform(hit.instance);
    in.prim = hit.prim;
    in.u = hit.u;
    in.v = hit.v;
    in.direction = ray.direction;
    in.cone_width = cone_width;
    in.fixed_mip_level = opt.fixed_mip_level;
    const SurfacePoint sp = make_surface_point(in, im.textures);
    if (depth == 0) {
      out.hit = true;
      out.backface = sp.backface;
      out.hit_distance = hit.t;
    }
    if (sp.backface) break;

    if (glm::any(glm::greaterThan(sp.emission, glm::vec3(0.0f)))) {
      float w = 1.0f;
      if (depth > 0) {
        const float light_pdf =
            im.lights.emissive_pdf(hit.instance, hit.prim, hit.t, std::abs(glm::dot(sp.ng, ray.direction)));
        w = power_heuristic(prev_bsdf_pdf, light_pdf);
      }
      add(beta * sp.emission * w, depth);
    }
    if (sp.unlit) break;  // KHR_materials_unlit reflects nothing
    if (depth >= opt.max_bounces) break;

    const glm::vec3 wo = sp.shading.to_local(-ray.direction);
    if (wo.z <= 0.0f) break;  // exactly grazing: nothing is reflected
    const Bsdf bsdf(sp.bsdf, wo);
    const glm::vec3 origin = offset_ray_origin(sp.position, sp.ng, sp.offset_scale);

    // Next-event estimation: every punctual light, then one point on the emissive triangles.
    for (const scene::Light& light : im.lights.punctual()) {
      LightSample ls;
      if (!sample_punctual(light, sp.position, ls) || glm::dot(ls.wi, sp.ng) <= 0.0f) continue;
      const glm::vec3 wi = sp.shading.to_local(ls.wi);
      const glm::vec3 f = bsdf.eval(wo, wi) * std::max(wi.z, 0.0f);
      if (!glm::any(glm::greaterThan(f, glm::vec3(0.0f)))) continue;
      glm::vec3 dir = ls.wi;
      float tmax = ls.distance;
      if (std::isfinite(ls.distance)) {
        const glm::vec3 d = ls.point - origin;
        tmax = glm::length(d);
        if (!(tmax > 0.0f)) continue;
        dir = d / tmax;
      }
      ++rays;
      if (im.embree.occluded(origin, dir, 0.0f, tmax, query)) continue;
      add(beta * f * ls.radiance, depth + 1);
    }
    if (im.lights.has_emissive()) {
      const float ux = sampler.next1d();
      const glm::vec2 uyz = sampler.next2d();
      LightSample ls;
      if (im.lights.sample_emissive(sp.position, {ux, uyz.x, uyz.y}, ls) && glm::dot(ls.wi, sp.ng) > 0.0f) {
        const glm::vec3 wi = sp.shading.to_local(ls.wi);
        const glm::vec3 f = bsdf.eval(wo, wi) * std::max(wi.z, 0.0f);
        if (glm::any(glm::greaterThan(f, glm::vec3(0.0f)))) {
          const glm::vec3 target = offset_ray_origin(ls.point, ls.normal, ls.point_magnitude);
          const glm::vec3 d = target - origin;
          const float len = glm::length(d);
          ++rays;
          if (len > 0.0f && !im.embree.occluded(origin, d / len, 0.0f, len, query)) {
            const float w = power_heuristic(ls.pdf, bsdf.pdf(wo, wi));
            add(beta * f * ls.radiance * (w / ls.pdf), depth + 1);
          }
        }
      }
    }

    if (im.environment && !im.environment->empty()) {
      EnvironmentSample es;
      if (im.environment->sample(sampler.next2d(), es) && glm::dot(es.wi, sp.ng) > 0.0f) {
        const glm::vec3 wi = sp.shading.to_local(es.wi);
        const glm::vec3 f = bsdf.eval(wo, wi) * std::max(wi.z, 0.0f);
        if (glm::any(glm::greaterThan(f, glm::vec3(0.0f)))) {
          ++rays;
          if (!im.embree.occluded(origin, es.wi, 0.0f, std::numeric_limits<float>::infinity(), query)) {
            const float w = power_heuristic(es.pdf, bsdf.pdf(wo, wi));
            add(beta * f * es.radiance * (w / es.pdf), depth + 1);
          }
        }
      }
    }

    // Continue the path by sampling the BSDF.
    const float u_lobe = sampler.next1d();
    const glm::vec2 u_dir = sampler.next2d();
    BsdfSample bs;
    if (!bsdf.sample(wo, {u_lobe, u_dir.x, u_dir.y}, bs) || !(bs.pdf > 0.0f)) break;
    const glm::vec3 wi = sp.shading.to_world(bs.wi);
    if (glm::dot(wi, sp.ng) <= 0.0f) break;  // reflection only: below the geometry is a leak
    beta *= bs.weight;
    prev_bsdf_pdf = bs.pdf;
    spread += std::min(1.0f, 1.0f / std::sqrt(bs.pdf));
    if (!valid_radiance(beta) || max_component(beta) <= 0.0f) break;

    if (depth + 1 >= opt.rr_min_bounces) {
      const float survive = std::clamp(max_component(beta), 0.05f, 1.0f);
      if (sampler.next1d() >= survive) break;
      beta /= survive;
    }
    ray = Ray{origin, wi, 0.0f, std::numeric_limits<float>::infinity(), 0.0f};
  }

  im.rays.fetch_add(rays, std::memory_order_relaxed);
  if (!valid_radiance(radiance)) {
    im.invalid.fetch_add(1, std::memory_order_relaxed);
    radiance = glm::vec3(0.0f);
  }
  out.radiance = radiance;
  return out;
}

}  // namespace ddish::trace
