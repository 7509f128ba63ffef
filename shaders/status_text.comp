// The live window's status text (display/status_font.h has the font and the layout): a dark box
// with lines of 5 × 7 glyphs, written into `image_count` images of width × height packed RGBA8
// (R in the low byte, row 0 at the top) lying one after another in the buffer: the composed
// image (atlas displays), or every gathered view before the lenticular interleave (so the text
// is a flat sign on the panel's plane, readable through the lenticules). One invocation per box
// pixel per image; pixels outside the image are left out. Opaque: drawing twice changes nothing.
#version 450

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, set = 0, binding = 0) buffer Images { uint images[]; };
layout(std430, set = 0, binding = 1) readonly buffer Cells { uint cells[]; };  // glyph indices
layout(std430, set = 0, binding = 2) readonly buffer Font { uint rows[]; };    // 7 per glyph

layout(push_constant) uniform Params {
  uint width;  // one image
  uint height;
  uint image_count;
  uint box_width;  // pixels, scaled
  uint box_height;
  uint scale;
  uint columns;
  uint lines;
  // The font's layout and colours, from display/status_font.h.
  uint glyph_width;
  uint glyph_height;
  uint cell_width;
  uint cell_height;
  uint padding;
  uint ink;
  uint paper;
} p;

void main() {
  const uint x = gl_GlobalInvocationID.x;
  const uint y = gl_GlobalInvocationID.y;
  const uint image = gl_GlobalInvocationID.z;
  if (x >= p.box_width || y >= p.box_height || x >= p.width || y >= p.height ||
      image >= p.image_count)
    return;
  const uint u = x / p.scale;  // unscaled box coordinates
  const uint v = y / p.scale;
  uint value = p.paper;
  if (u >= p.padding && v >= p.padding) {
    const uint column = (u - p.padding) / p.cell_width, cx = (u - p.padding) % p.cell_width;
    const uint line = (v - p.padding) / p.cell_height, cy = (v - p.padding) % p.cell_height;
    if (column < p.columns && line < p.lines && cx < p.glyph_width && cy < p.glyph_height) {
      const uint glyph = cells[line * p.columns + column];
      if ((rows[glyph * p.glyph_height + cy] & (1u << (p.glyph_width - 1u - cx))) != 0u) value = p.ink;
    }
  }
  images[(image * p.height + y) * p.width + x] = value;
}
