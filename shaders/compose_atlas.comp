// The window's image of a single view, a stereo pair or a quilt, composed on the GPU from the
// frame's views (display/gpu_compositor.h): packed RGBA8 display values in, the same packing out,
// no filtering. View v sits in tile v of the atlas, view 0 at the bottom-left (QuiltLayout::tile);
// pixels no tile covers (a quilt's spare right column and top row, its empty cells) are black.
#version 450

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, set = 0, binding = 0) readonly buffer Views { uint views[]; };  // view after view
layout(std430, set = 0, binding = 1) writeonly buffer Out { uint image[]; };

layout(push_constant) uniform Params {
  uint width;        // atlas
  uint height;
  uint tile_width;   // one view
  uint tile_height;
  uint columns;
  uint rows;
  uint view_count;
} p;

void main() {
  const uint x = gl_GlobalInvocationID.x;
  const uint y = gl_GlobalInvocationID.y;
  if (x >= p.width || y >= p.height) return;
  const uint from_bottom = p.height - 1u - y;
  const uint column = x / p.tile_width;
  const uint row = from_bottom / p.tile_height;  // rows of tiles from the bottom
  uint value = 0xFF000000u;                      // opaque black
  if (column < p.columns && row < p.rows) {
    const uint view = row * p.columns + column;
    if (view < p.view_count) {
      const uint tx = x - column * p.tile_width;
      const uint ty = y - (p.height - (row + 1u) * p.tile_height);
      value = views[(view * p.tile_height + ty) * p.tile_width + tx];
    }
  }
  image[y * p.width + x] = value;
}
