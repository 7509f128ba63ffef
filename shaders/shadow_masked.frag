// Shadow pass for alpha-masked materials: texels below the material's cutoff cast no shadow,
// the same test forward_main.glsl applies to what the camera sees. The material set is bound
// as set 1 here (set 0 is the frame); only its factors and base-colour texture are read.
#version 460

layout(set = 1, binding = 0) uniform MaterialData {
  vec4 base_color;
  vec4 emission;
  vec4 params;
  vec4 alpha;  // x: cutoff, y: 1 = MASK, z: bit set of bound textures
} material;
layout(set = 1, binding = 1) uniform sampler2D base_color_tex;

layout(location = 0) in vec2 in_uv;

void main() {
  float a = material.base_color.a;
  if ((uint(material.alpha.z) & 1u) != 0u) a *= texture(base_color_tex, in_uv).a;
  if (a < material.alpha.x) discard;
}
