// The Looking Glass panel image built on the GPU from the frame's views, equal bit for bit to
// display::interleave (src/display/lenticular.cpp) on the quilt of the same display values.
// What depends on the calibration alone is computed once on the CPU by lenticular.cpp's own
// functions and read from tables here: the view each subpixel shows (subpixel_view) and each
// column's and row's bilinear tap (tile_tap_x / tile_tap_y). What remains is the CPU's float
// arithmetic, in its order and without fused multiply-adds (`precise`): decode the four texels'
// sRGB bytes through the same 256-entry table, two lerps along x, one along y, encode through the
// same 255 midpoints (metrics::srgb8_encode's upper_bound).
#version 450

layout(local_size_x = 8, local_size_y = 8) in;

struct Tap {
  int i0;
  int i1;
  float f;
  int unused;
};

layout(std430, set = 0, binding = 0) readonly buffer Views { uint views[]; };  // view after view
layout(std430, set = 0, binding = 1) writeonly buffer Out { uint image[]; };
// Per panel pixel, the views of red, green and blue in bits 0-7, 8-15, 16-23.
layout(std430, set = 0, binding = 2) readonly buffer SubpixelViews { uint subpixel_views[]; };
layout(std430, set = 0, binding = 3) readonly buffer Columns { Tap columns[]; };
layout(std430, set = 0, binding = 4) readonly buffer Rows { Tap rows[]; };
// decoded[256] (srgb8_decode of each byte) then midpoint[255] (srgb8_encode's thresholds).
layout(std430, set = 0, binding = 5) readonly buffer Srgb { float srgb[]; };

layout(push_constant) uniform Params {
  uint width;  // panel
  uint height;
  uint tile_width;
  uint tile_height;
} p;

float decoded(uint texel, uint channel) { return srgb[(texel >> (8u * channel)) & 0xFFu]; }

uint encode(float v) {
  if (!(v > 0.0)) return 0u;
  uint lo = 0u, hi = 255u;  // the first midpoint above v, as std::upper_bound finds it
  while (lo < hi) {
    const uint mid = (lo + hi) / 2u;
    if (srgb[256u + mid] <= v)
      lo = mid + 1u;
    else
      hi = mid;
  }
  return lo;
}

void main() {
  const uint x = gl_GlobalInvocationID.x;
  const uint y = gl_GlobalInvocationID.y;
  if (x >= p.width || y >= p.height) return;
  const Tap tx = columns[x];
  const Tap ty = rows[y];
  const uint chosen = subpixel_views[y * p.width + x];
  uint value = 0xFF000000u;
  for (uint c = 0u; c < 3u; ++c) {
    const uint base = ((chosen >> (8u * c)) & 0xFFu) * p.tile_width * p.tile_height;
    const float a = decoded(views[base + uint(ty.i0) * p.tile_width + uint(tx.i0)], c);
    const float b = decoded(views[base + uint(ty.i0) * p.tile_width + uint(tx.i1)], c);
    const float d = decoded(views[base + uint(ty.i1) * p.tile_width + uint(tx.i0)], c);
    const float e = decoded(views[base + uint(ty.i1) * p.tile_width + uint(tx.i1)], c);
    precise float top = a + (b - a) * tx.f;
    precise float bottom = d + (e - d) * tx.f;
    precise float s = top + (bottom - top) * ty.f;
    value |= encode(s) << (8u * c);
  }
  image[y * p.width + x] = value;
}
