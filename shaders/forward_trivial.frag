// Forward pass with a trivial fragment stage (RendererOptions::shading = trivial, raster/shading.h):
// one constant colour, no descriptors read, no discard (so early depth testing stays on). Drawn
// with forward.vert / forward_layered.vert into the same target as the full shading, its time is
// the vertex + raster + fill floor of a view. The colour is raster::kTrivialColor.
#version 460

layout(location = 0) out vec4 out_color;

void main() { out_color = vec4(0.5, 0.25, 0.125, 1.0); }
