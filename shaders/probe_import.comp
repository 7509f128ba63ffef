#version 460
// The GPU-to-GPU probe hand-off (src/raster/probe_import.h): converts the listed probes' fp32
// running averages, as the GPU probe tracer keeps them (src/trace_vk/vk_probe_tracer.h), into
// the rasterizer's probe data, into a device buffer laid out exactly like ProbeTextures' host
// staging (probe_textures.cpp), which the same copy commands then move into the SH textures and
// the moment buffer. Each value becomes a half as raster::pack_probe_slots and
// pack_probe_moments make it on the CPU (sh::float_to_half's rounding, to nearest even, with
// their saturation and counts of what fp16 cannot hold), so the two paths write the same bits.
// One work group per listed probe (several when there are more probes than groups).

layout(local_size_x = 64) in;

struct Item {
  uint probe;        // its index in the volume (and in the source buffers); bit 31: active
  float offset[3];   // its relocation offset, metres (the visibility record's last 3 uints)
};
const uint kActive = 0x80000000u;

// Probe, coefficient, RGB (probes::ProbeVolume's layout).
layout(std430, binding = 0) readonly buffer Coefficients { float coefficients[]; };
// Probe, texel: (mean d, mean d^2) / (range, range^2).
layout(std430, binding = 1) readonly buffer Moments { vec2 moments[]; };
layout(std430, binding = 2) readonly buffer Items { Item items[]; };
// Texture t's texel of listed probe k at uints 2 (t n + k) and +1 (halves 4 slot..4 slot+3, low
// half first); then at texel_uints the moment header and the listed probes' records.
layout(std430, binding = 3) writeonly buffer Staging { uint staging[]; };
// [0]: values beyond fp16 saturated; [1]: NaN or Inf replaced (raster::SlotClamps).
layout(std430, binding = 4) buffer Clamps { uint clamps[]; };

layout(push_constant) uniform Params {
  uint count;             // listed probes
  uint source_coeffs;     // coefficients per probe in the source (the volume's order)
  uint order_coeffs;      // coefficients the textures hold (their order)
  uint texture_count;     // RGBA16F textures
  uint texels;            // moment texels per probe (0: no moment buffer)
  uint record_uints;      // texels + 3
  uint texel_uints;       // where the moment header starts in the staging buffer
  uint relocated;         // the header's uint 0
} params;

// sh::float_to_half, bit for bit: round to nearest, ties to even; NaN stays NaN, >= 65520 is Inf.
uint round_shift(uint m, uint shift) {
  const uint q = m >> shift;
  const uint rem = m & ((1u << shift) - 1u);
  const uint halfway = 1u << (shift - 1u);
  return (rem > halfway || (rem == halfway && (q & 1u) != 0u)) ? q + 1u : q;
}

uint float_to_half(float f) {
  const uint u = floatBitsToUint(f);
  const uint sign = (u >> 16) & 0x8000u;
  const uint a = u & 0x7fffffffu;
  if (a > 0x7f800000u) return sign | 0x7e00u;
  if (a >= 0x477ff000u) return sign | 0x7c00u;
  if (a >= 0x38800000u) return sign | round_shift(a - 0x38000000u, 13u);
  if (a <= 0x33000000u) return sign;
  const uint m = (a & 0x7fffffu) | 0x800000u;
  return sign | round_shift(m, 126u - (a >> 23));
}

const float kHalfMax = 65504.0;

// raster::to_half (probe_slots.cpp): NaN as 0, +-Inf and beyond-range values saturated, counted.
uint to_half(float v) {
  if (isnan(v)) {
    atomicAdd(clamps[1], 1u);
    return float_to_half(0.0);
  }
  if (isinf(v)) {
    atomicAdd(clamps[1], 1u);
    return float_to_half(v > 0.0 ? kHalfMax : -kHalfMax);
  }
  if (abs(v) > kHalfMax) {
    atomicAdd(clamps[0], 1u);
    return float_to_half(v > 0.0 ? kHalfMax : -kHalfMax);
  }
  return float_to_half(v);
}

// Slot s of an item (pack_probe_slots): 0 the weight, then coefficient (s - 1) / 3's channel,
// bands above either order zero.
uint slot_half(Item item, uint s) {
  if (s == 0u) return float_to_half((item.probe & kActive) != 0u ? 1.0 : 0.0);
  if ((item.probe & kActive) == 0u) return 0u;
  const uint i = (s - 1u) / 3u;
  if (i >= params.order_coeffs || i >= params.source_coeffs) return 0u;
  return to_half(coefficients[((item.probe & ~kActive) * params.source_coeffs + i) * 3u + (s - 1u) % 3u]);
}

void main() {
  const uint lane = gl_LocalInvocationID.x;
  if (gl_GlobalInvocationID.x == 0u && params.texels > 0u) {
    staging[params.texel_uints] = params.relocated;
    for (uint h = 1u; h < 4u; ++h) staging[params.texel_uints + h] = 0u;
  }
  for (uint k = gl_WorkGroupID.x; k < params.count; k += gl_NumWorkGroups.x) {
    const Item item = items[k];
    // Two uints per texel: slots 4t, 4t+1 and 4t+2, 4t+3.
    for (uint j = lane; j < 2u * params.texture_count; j += 64u) {
      const uint t = j / 2u;
      const uint s = 4u * t + 2u * (j % 2u);
      staging[2u * (t * params.count + k) + j % 2u] = slot_half(item, s) | (slot_half(item, s + 1u) << 16);
    }
    if (params.texels == 0u) continue;
    const uint rec = params.texel_uints + 4u + k * params.record_uints;
    for (uint t = lane; t < params.texels; t += 64u) {
      const vec2 m = moments[(item.probe & ~kActive) * params.texels + t];
      staging[rec + t] = to_half(m.x) | (to_half(m.y) << 16);
    }
    if (lane < 3u) staging[rec + params.texels + lane] = floatBitsToUint(item.offset[lane]);
  }
}
