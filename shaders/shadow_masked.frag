// Shadow pass for alpha-masked materials: texels below the material's cutoff cast no shadow,
// the same test forward_main.glsl applies to what the camera sees (vertex alpha, base-colour
// texture on its UV set through its KHR_texture_transform). The material set is bound as set 1
// here (set 0 is the frame); only its factors, base-colour transform and texture are read.
#version 460

layout(set = 1, binding = 0) uniform MaterialData {
  vec4 base_color;
  vec4 emission;
  vec4 params;
  vec4 alpha;  // x: cutoff, y: 1 = MASK, z: bit set of bound textures
  vec4 uv_rows[2];  // the base-colour slot's transform rows (raster/gpu_types.h)
} material;
layout(set = 1, binding = 1) uniform sampler2D base_color_tex;

layout(location = 0) in vec4 in_uv;
layout(location = 1) in float in_alpha;

void main() {
  float a = material.base_color.a * in_alpha;
  if ((uint(material.alpha.z) & 1u) != 0u) {
    const vec3 uv = vec3(material.uv_rows[0].w > 0.5 ? in_uv.zw : in_uv.xy, 1.0);
    a *= texture(base_color_tex, vec2(dot(material.uv_rows[0].xyz, uv), dot(material.uv_rows[1].xyz, uv))).a;
  }
  if (a < material.alpha.x) discard;
}
