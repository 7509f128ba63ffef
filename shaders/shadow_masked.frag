// Shadow pass for alpha-masked and blended materials: texels below the material's cutoff cast
// no shadow, the same test forward_main.glsl applies to what the camera sees (vertex alpha,
// base-colour texture on its UV set through its KHR_texture_transform). A BLEND caster is
// alpha-tested against an ordered 4 x 4 dither instead of a cutoff: it covers a fraction alpha
// of the map's texels, so the 3 x 3 PCF lookup, whose footprint spans about 4 x 4 texels, lets
// 1 - alpha of the light through, as the path tracer's alpha-as-coverage shadow rays do. The
// material set is bound as set 1 here (set 0 is the frame); only its factors, base-colour
// transform and texture are read.
#version 460

layout(set = 1, binding = 0) uniform MaterialData {
  vec4 base_color;
  vec4 emission;
  vec4 params;
  vec4 alpha;  // x: cutoff, y: 1 = MASK, z: bit set of bound textures, w: 1 = BLEND
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
  if (material.alpha.w > 0.5) {
    // Bayer's 4 x 4 matrix: each of the 16 thresholds (k + 0.5) / 16 once per 4 x 4 block.
    const uvec2 q = uvec2(gl_FragCoord.xy) & 3u;
    const uint bayer[16] = uint[16](0u, 8u, 2u, 10u, 12u, 4u, 14u, 6u, 3u, 11u, 1u, 9u, 15u, 7u, 13u, 5u);
    if (a <= (float(bayer[q.y * 4u + q.x]) + 0.5) / 16.0) discard;
  } else if (a < material.alpha.x) {
    discard;
  }
}
