#version 460
// The GPU probe tracer's second step (src/trace_vk/vk_probe_tracer.h): one work group per traced
// probe projects its paths' radiance onto SH (weight 4 pi / N per lattice direction, as
// probes::ProbeTracer::trace_probe does), counts back-face first hits and invalid paths,
// classifies a probe on its first update (more back faces than the limit: inside geometry, its
// coefficients zeroed as ProbeVolume::deactivate does), and blends the estimate into the
// GPU-resident running average with the weight the host computed from the probe's history
// (probes/accumulation.h).
#extension GL_GOOGLE_include_directive : require
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
  uint pad;
};

struct Result {
  uint backfaces;
  uint invalid;
  uint inside;  // classified inside geometry by this update
  uint rays;    // rays the probe's paths cast
};

layout(std430, binding = 0) readonly buffer PathOut { vec4 path_out[]; };
layout(std430, binding = 1) readonly buffer Directions { vec4 lattice[]; };
layout(std430, binding = 2) readonly buffer Work { ProbeWork work[]; };
layout(std430, binding = 3) readonly buffer Blends { Blend blends[]; };
layout(std430, binding = 4) buffer Coefficients { float coefficients[]; };  // probe, coefficient, RGB
layout(std430, binding = 5) writeonly buffer Results { Result results[]; };

layout(push_constant) uniform Params {
  uint samples;
  uint order;
  uint work_count;
} params;

const uint PATH_BACKFACE = 1u;
const uint PATH_INVALID = 4u;
const uint PATH_RAYS_SHIFT = 8u;
const float FOUR_PI = 12.566370614359172;

shared float reduce[64];
shared float sums[SH_MAX_COEFFS * 3];
shared uint backfaces;
shared uint invalid;
shared uint rays;

void main() {
  const uint w = gl_WorkGroupID.x;
  const uint lane = gl_LocalInvocationID.x;
  const uint n = params.samples;
  const int count = SH_COEFF_COUNT(int(params.order));
  if (lane == 0u) {
    backfaces = 0u;
    invalid = 0u;
    rays = 0u;
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
    if ((flags & PATH_INVALID) != 0u) {
      ++my_invalid;
      continue;
    }
    float y[SH_MAX_COEFFS];
    sh_basis(normalize(rotation * lattice[i].xyz), int(params.order), y);
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

  const Blend blend = blends[w];
  const bool inside = blend.backface_limit != 0xFFFFFFFFu && backfaces > blend.backface_limit;
  const uint base = blend.probe * uint(count) * 3u;
  for (uint j = lane; j < uint(count) * 3u; j += 64u) {
    const float e = sums[j];
    const float avg = coefficients[base + j];
    // w == 1 assigns, so the zero start leaves no trace (ProbeVolume::accumulate).
    coefficients[base + j] = inside ? 0.0 : (blend.weight == 1.0 ? e : avg + blend.weight * (e - avg));
  }
  if (lane == 0u) results[w] = Result(backfaces, invalid, inside ? 1u : 0u, rays);
}
