#version 460
// The GPU probe tracer's second step (src/trace_vk/vk_probe_tracer.h): one work group per traced
// probe projects its paths' radiance onto SH (weight 4 pi / N per lattice direction, as
// probes::ProbeTracer::trace_probe does), bins their first-hit distances into the probe's
// octahedral distance moments (probes::MomentEstimate's rules: clamped to the range and divided
// by it, a miss counts as the range; summed in fixed point, so each texel's sum is exact and
// independent of the order the lanes add in), counts back-face first hits and invalid paths, finds the
// nearest front and back first hits of a probe being classified (for relocation), classifies a
// probe on its first update (more back faces than the limit: inside geometry, its coefficients
// zeroed and its moments reset as ProbeVolume::deactivate does), and blends both estimates into
// the GPU-resident running averages with the weight the host computed from the probe's history
// (probes/accumulation.h). A dry item only reports: the host decides relocation from it.
#extension GL_GOOGLE_include_directive : require
#include "octahedral.glsl"
#include "sh_basis.glsl"

layout(local_size_x = 64) in;

struct ProbeWork {
  vec4 origin;       // w: the probe index (bits)
  vec4 rotation[3];  // columns of the probe's random rotation of the lattice
};

struct Blend {
  uint probe;
  float weight;          // the running average's weight of this update; 1: assign
  uint backface_limit;   // > this many back-face first hits: inside geometry; ~0u: not classified
  uint flags;            // BLEND_DRY: report only, blend nothing
};

struct Result {
  uint backfaces;
  uint invalid;
  uint inside;  // classified inside geometry by this update
  uint rays;    // rays the probe's paths cast
  // Of a probe being classified: the nearest back- and front-face first hits (float bits,
  // infinity: none) and the first path that reached each (~0u: none).
  uint nearest_back;
  uint back_path;
  uint nearest_front;
  uint front_path;
};

layout(std430, binding = 0) readonly buffer PathOut { vec4 path_out[]; };
layout(std430, binding = 1) readonly buffer Directions { vec4 lattice[]; };
layout(std430, binding = 2) readonly buffer Work { ProbeWork work[]; };
layout(std430, binding = 3) readonly buffer Blends { Blend blends[]; };
layout(std430, binding = 4) buffer Coefficients { float coefficients[]; };  // probe, coefficient, RGB
layout(std430, binding = 5) writeonly buffer Results { Result results[]; };
layout(std430, binding = 6) readonly buffer PathDistance { float path_distance[]; };
// Probe, texel: (mean d, mean d^2) / (range, range^2), as ProbeVolume keeps them.
layout(std430, binding = 7) buffer Moments { vec2 moments[]; };

layout(push_constant) uniform Params {
  uint samples;
  uint order;
  uint work_count;
  uint moment_resolution;  // 0: the volume keeps no moments
  float moment_range;
  // Fixed-point steps per unit of (d / range) and (d / range)^2: a power of two no larger than
  // 2^32 / samples, so no texel's sum of up to `samples` values overflows.
  float moment_scale;
} params;

const uint PATH_BACKFACE = 1u;
const uint PATH_HIT = 2u;
const uint PATH_INVALID = 4u;
const uint PATH_RAYS_SHIFT = 8u;
const uint BLEND_DRY = 1u;
const float FOUR_PI = 12.566370614359172;
const uint INF_BITS = 0x7F800000u;
const uint MAX_TEXELS = 256u;  // kMaxMomentResolution^2

shared float reduce[64];
shared float sums[SH_MAX_COEFFS * 3];
shared uint backfaces;
shared uint invalid;
shared uint rays;
shared uint nearest_bits[2];  // back, front
shared uint nearest_path[2];
// Per texel: the fixed-point sums of d / range and (d / range)^2, and the paths.
shared uint texel_d[MAX_TEXELS];
shared uint texel_d2[MAX_TEXELS];
shared uint texel_paths[MAX_TEXELS];

void main() {
  const uint w = gl_WorkGroupID.x;
  const uint lane = gl_LocalInvocationID.x;
  const uint n = params.samples;
  const int count = SH_COEFF_COUNT(int(params.order));
  const Blend blend = blends[w];
  const bool classifying = blend.backface_limit != 0xFFFFFFFFu;
  if (lane == 0u) {
    backfaces = 0u;
    invalid = 0u;
    rays = 0u;
    nearest_bits[0] = INF_BITS;
    nearest_bits[1] = INF_BITS;
    nearest_path[0] = 0xFFFFFFFFu;
    nearest_path[1] = 0xFFFFFFFFu;
  }
  const uint res = params.moment_resolution;
  const uint texels = res * res;
  for (uint t = lane; t < texels; t += 64u) {
    texel_d[t] = 0u;
    texel_d2[t] = 0u;
    texel_paths[t] = 0u;
  }
  barrier();

  const ProbeWork pw = work[w];
  const mat3 rotation = mat3(pw.rotation[0].xyz, pw.rotation[1].xyz, pw.rotation[2].xyz);
  const float weight = FOUR_PI / float(n);
  float acc[SH_MAX_COEFFS * 3];
  for (int j = 0; j < SH_MAX_COEFFS * 3; ++j) acc[j] = 0.0;
  uint my_backfaces = 0u, my_invalid = 0u, my_rays = 0u;
  for (uint i = lane; i < n; i += 64u) {
    const vec4 p = path_out[w * n + i];
    const uint flags = floatBitsToUint(p.w);
    if ((flags & PATH_BACKFACE) != 0u) ++my_backfaces;
    my_rays += flags >> PATH_RAYS_SHIFT;
    // Distances are geometry: a path with invalid radiance still counts (ProbeTracer).
    if (classifying && (flags & PATH_HIT) != 0u)
      atomicMin(nearest_bits[(flags & PATH_BACKFACE) != 0u ? 0 : 1], floatBitsToUint(path_distance[w * n + i]));
    const vec3 dir = normalize(rotation * lattice[i].xyz);
    if (res > 0u) {
      const float range = params.moment_range;
      const float d = (flags & PATH_HIT) != 0u ? min(max(path_distance[w * n + i], 0.0), range) / range : 1.0;
      const uint t = octahedral_texel(dir, res);
      atomicAdd(texel_d[t], uint(d * params.moment_scale + 0.5));
      atomicAdd(texel_d2[t], uint(d * d * params.moment_scale + 0.5));
      atomicAdd(texel_paths[t], 1u);
    }
    if ((flags & PATH_INVALID) != 0u) {
      ++my_invalid;
      continue;
    }
    float y[SH_MAX_COEFFS];
    sh_basis(dir, int(params.order), y);
    for (int j = 0; j < count; ++j) {
      acc[3 * j] += p.r * y[j] * weight;
      acc[3 * j + 1] += p.g * y[j] * weight;
      acc[3 * j + 2] += p.b * y[j] * weight;
    }
  }
  atomicAdd(backfaces, my_backfaces);
  atomicAdd(invalid, my_invalid);
  atomicAdd(rays, my_rays);
  for (int j = 0; j < count * 3; ++j) {
    reduce[lane] = acc[j];
    barrier();
    for (uint stride = 32u; stride > 0u; stride >>= 1) {
      if (lane < stride) reduce[lane] += reduce[lane + stride];
      barrier();
    }
    if (lane == 0u) sums[j] = reduce[0];
    barrier();
  }
  if (classifying) {
    // The first path at the nearest distance, as ProbeTracer keeps the first strictly nearer.
    for (uint i = lane; i < n; i += 64u) {
      const uint flags = floatBitsToUint(path_out[w * n + i].w);
      if ((flags & PATH_HIT) == 0u) continue;
      const uint k = (flags & PATH_BACKFACE) != 0u ? 0u : 1u;
      if (floatBitsToUint(path_distance[w * n + i]) == nearest_bits[k]) atomicMin(nearest_path[k], i);
    }
  }

  barrier();

  const bool dry = (blend.flags & BLEND_DRY) != 0u;
  const bool inside = !dry && classifying && backfaces > blend.backface_limit;
  if (lane == 0u)
    results[w] = Result(backfaces, invalid, inside ? 1u : 0u, rays, nearest_bits[0], nearest_path[0],
                        nearest_bits[1], nearest_path[1]);
  if (dry) return;
  const uint base = blend.probe * uint(count) * 3u;
  for (uint j = lane; j < uint(count) * 3u; j += 64u) {
    const float e = sums[j];
    const float avg = coefficients[base + j];
    // w == 1 assigns, so the zero start leaves no trace (ProbeVolume::accumulate).
    coefficients[base + j] = inside ? 0.0 : (blend.weight == 1.0 ? e : avg + blend.weight * (e - avg));
  }
  const uint moment_base = blend.probe * texels;
  for (uint t = lane; t < texels; t += 64u) {
    // Inside geometry: reset to "nothing in the way"; texels no path reached keep their value.
    if (inside) {
      moments[moment_base + t] = vec2(1.0);
    } else if (texel_paths[t] > 0u) {
      const vec2 e = vec2(float(texel_d[t]), float(texel_d2[t])) / (params.moment_scale * float(texel_paths[t]));
      const vec2 avg = moments[moment_base + t];
      moments[moment_base + t] = blend.weight == 1.0 ? e : avg + blend.weight * (e - avg);
    }
  }
}
