// Indirect light from the SH probe volume (src/raster/probe_textures.h uploads it) and the BRDF
// tables of the split-sum approximation (src/raster/brdf_tables.h). A forward shader computes
//   indirect = albedo (1 - metallic) (1 - E(NoV, roughness)) / pi
//                * probe_irradiance(p, n) * occlusion
//            + (F0 dfg.x + dfg.y) * probe_specular(p, reflect(-v, n), roughness),
//   dfg = brdf_dfg(NoV, roughness),
// which matches the path tracer's BSDF (src/trace/bsdf.cpp) under the probes' radiance; E is the
// dielectric layer's directional albedo (surface_lighting.glsl reads it from the tracer's table).
// probe_lighting(p, n, reflect(-v, n), roughness, E, L) returns both probe terms from one
// interpolation (half the fetches); probe_interpolate + probe_sh_irradiance/probe_sh_specular
// are the pieces, for shaders that want the interpolated SH themselves.
//
// Defines the includer may set before the #include:
//   PROBE_SET       descriptor set of ProbeTextures (default 1)
//   BRDF_SET        descriptor set of BrdfTables (default 2)
//   PROBE_SH_ORDER  SH order evaluated, 1..4 (default 2); at most ProbeTextures::order(), and
//                   lower orders fetch fewer textures and evaluate fewer bands.
//
// Texture layout (ProbeTextures): probe (x, y, z) of the grid is texel (x, y, z) of every
// RGBA16F 3D texture probe_sh[t]. Each probe holds the slots s[0..] = (w, w c0.r, w c0.g,
// w c0.b, w c1.r, ...), slot k in component k % 4 of texture k / 4, where w is its validity (1,
// or 0 for an inactive probe) and c_i the RGB radiance coefficient of Y_i. Because the
// coefficients are stored premultiplied by w, one hardware-trilinear fetch per texture gives
// sum t_i w_i c_i and sum t_i w_i over the 8 probes around p, and their ratio is the
// trilinear interpolation with inactive probes weighted out and the rest renormalised.
//
// Visibility (a volume with distance moments, probes/moment_map.h; probe_grid.visibility.x > 0):
// each of the 8 probes gets DDGI's weight (Majercik et al. 2019): trilinear x backface
// ((1 + cos)/2)^2 + 0.2 x Chebyshev's bound P(d >= r) <= var / (var + (r - mean)^2), cubed, taken
// at the point moved visibility.w (0.2 n + 0.8 v) off the surface so that it does not shadow
// itself, and crushed below 0.2 (w^3 / 0.04). The moments come from probe_moments (binding 2: a
// header of PROBE_MOMENT_HEADER uints, uint 0 non-zero when some probe is relocated; then probe
// i's record at PROBE_MOMENT_HEADER + i * (R^2 + 3): its R x R octahedral texels, each
// packHalf2x16(mean d, mean d^2) divided by the range visibility.z, then its relocation offset as
// 3 float bits; the probe's distances and directions are measured from its relocated position.
// Without relocated probes the 24 offset reads per pixel are skipped: on lavapipe each is a
// per-lane gather, and the offsets are all zero then). The weights are then folded into the
// trilinear fractions, per axis the share on the upper probes, and the textures are fetched once
// at the moved point: exact
// when the weights are a product over the axes (a wall across an axis hides a face of the cell),
// an approximation otherwise, at a fraction of the cost of reading the 8 probes one by one
// (docs/probe-visibility.md has the measurements). A volume without moments takes the plain
// hardware-trilinear path above.
#ifndef DDISH_PROBE_LIGHTING_GLSL
#define DDISH_PROBE_LIGHTING_GLSL

#extension GL_GOOGLE_include_directive : enable
#include "octahedral.glsl"
#include "sh_basis.glsl"

#ifndef PROBE_SET
#define PROBE_SET 1
#endif
#ifndef BRDF_SET
#define BRDF_SET 2
#endif
#ifndef PROBE_SH_ORDER
#define PROBE_SH_ORDER 2
#endif
#if PROBE_SH_ORDER < 1 || PROBE_SH_ORDER > 4
#error "PROBE_SH_ORDER must be 1..4"
#endif

#define PROBE_SH_COEFFS SH_COEFF_COUNT(PROBE_SH_ORDER)
#define PROBE_SH_TEXTURES ((1 + 3 * PROBE_SH_COEFFS + 3) / 4)
#define BRDF_GGX_ZH_NODES 65
#define PROBE_MOMENT_HEADER 4u  // raster::kMomentHeaderUints

// Set PROBE_SET, binding 0: the grid (raster::ProbeGridUniform, std140).
layout(set = PROBE_SET, binding = 0, std140) uniform ProbeGridBlock {
  vec4 origin;       // xyz: world position of probe (0, 0, 0); w: the textures' SH order
  vec4 inv_spacing;  // xyz: 1 / cell size (0 on an axis of zero extent)
  vec4 counts;       // xyz: probes per axis; w: number of probe_sh textures
  vec4 bounds_min;   // xyz: the volume's bounds (probe 0 sits half a cell inside)
  vec4 cell_size;    // xyz: distance between neighbouring probes
  vec4 visibility;   // x: moment map resolution R (0: no moments); y: record stride R * R + 3;
                     // z: moment range (metres); w: bias distance (metres)
} probe_grid;
// Set PROBE_SET, binding 1: the slot textures, linear filtering, clamped to the edge.
layout(set = PROBE_SET, binding = 1) uniform sampler3D probe_sh[PROBE_SH_TEXTURES];
// Set PROBE_SET, binding 2: the moment maps (read only when visibility.x > 0).
layout(set = PROBE_SET, binding = 2, std430) readonly buffer ProbeMoments { uint probe_moments[]; };

// Set BRDF_SET, binding 0: DFG (scale, bias) over (cbrt(n.v), roughness), nodes at texel
// centres (raster::DfgTable).
layout(set = BRDF_SET, binding = 0) uniform sampler2D brdf_dfg_table;
// Set BRDF_SET, binding 1: sh::ggx_zh_table(), bands 1..4 in xyzw, node j at roughness j / 64.
layout(set = BRDF_SET, binding = 1, std140) uniform BrdfGgxZhBlock {
  vec4 brdf_ggx_zh_nodes[BRDF_GGX_ZH_NODES];
};

const float PROBE_PI = 3.14159265358979;

// Fetches slot texture t at uvw into s[4t .. 4t+3]; the #if keeps constant indices in range.
// Explicit LOD 0: the textures have one level, and an implicit-LOD fetch makes lavapipe compute
// derivatives and a level per fetch (on Mesa 25, one Sponza view at MSAA 4: 430 against 586 ms of
// CPU per frame in one paired run on a loaded machine, so roughly, not exactly, a quarter).
#define PROBE_FETCH(t) { const vec4 v_ = textureLod(probe_sh[t], uvw, 0.0); \
  s[4 * t] = v_.x; s[4 * t + 1] = v_.y; s[4 * t + 2] = v_.z; s[4 * t + 3] = v_.w; }

void probe_fetch_slots(vec3 uvw, out float s[4 * PROBE_SH_TEXTURES]) {
  PROBE_FETCH(0)
  PROBE_FETCH(1)
#if PROBE_SH_TEXTURES > 2
  PROBE_FETCH(2)
  PROBE_FETCH(3)
#endif
#if PROBE_SH_TEXTURES > 4
  PROBE_FETCH(4)
  PROBE_FETCH(5)
  PROBE_FETCH(6)
#endif
#if PROBE_SH_TEXTURES > 7
  PROBE_FETCH(7)
  PROBE_FETCH(8)
  PROBE_FETCH(9)
  PROBE_FETCH(10)
  PROBE_FETCH(11)
  PROBE_FETCH(12)
#endif
#if PROBE_SH_TEXTURES > 13
  PROBE_FETCH(13)
  PROBE_FETCH(14)
  PROBE_FETCH(15)
  PROBE_FETCH(16)
  PROBE_FETCH(17)
  PROBE_FETCH(18)
#endif
}

vec3 probe_uvw(vec3 g) { return (g + 0.5) / probe_grid.counts.xyz; }

// Without visibility: the hardware-trilinear fetches.
bool probe_interpolate_trilinear(vec3 world_pos, out vec3 sh[PROBE_SH_COEFFS]) {
  const vec3 last = probe_grid.counts.xyz - 1.0;
  const vec3 g = clamp((world_pos - probe_grid.origin.xyz) * probe_grid.inv_spacing.xyz,
                       vec3(0.0), last);
  float s[4 * PROBE_SH_TEXTURES];
  probe_fetch_slots(probe_uvw(g), s);
  if (!(s[0] > 0.0)) {
    // The weights vanish exactly on an inactive probe (and, on hardware with 8-bit filter
    // fractions, within 1/512 cell of it), though active probes share the cell: look again a
    // quarter of the way to the cell's centre, which weights them in. Zero there too means
    // that all 8 probes are inactive.
    const vec3 base = clamp(floor(g), vec3(0.0), max(last - 1.0, vec3(0.0)));
    probe_fetch_slots(probe_uvw(mix(g, min(base + 0.5, last), 0.25)), s);
  }
  const float w = s[0];
  const float inv_w = w > 0.0 ? 1.0 / w : 0.0;
  for (int i = 0; i < PROBE_SH_COEFFS; ++i)
    sh[i] = vec3(s[1 + 3 * i], s[2 + 3 * i], s[3 + 3 * i]) * inv_w;
  return w > 0.0;
}

// Chebyshev's one-sided bound on P(distance >= r) for a probe whose rays in that direction met
// geometry at mean distance m with mean square m2 (all in units of the moment range), cubed as in
// DDGI to darken the bound's soft tail; 1 when r is no farther than the mean.
float probe_chebyshev(float r, float m, float m2) {
  if (r <= m) return 1.0;
  const float variance = max(m2 - m * m, 1e-4);  // fp16 moments: keep a floor
  const float d = r - m;
  const float p = variance / (variance + d * d);
  return p * p * p;
}

// The visibility weights W of the 8 probes folded into the trilinear fractions, per axis the
// share of the weight on the upper probes, t'_a = sum_{o_a = 1} W / sum W; then one
// hardware-trilinear fetch per texture at the moved point, whose validity weight still leaves
// out inactive probes.
bool probe_interpolate_visible(vec3 world_pos, vec3 normal, vec3 to_viewer,
                               out vec3 sh[PROBE_SH_COEFFS]) {
  const ivec3 counts = ivec3(probe_grid.counts.xyz);
  const vec3 last = probe_grid.counts.xyz - 1.0;
  const vec3 g = clamp((world_pos - probe_grid.origin.xyz) * probe_grid.inv_spacing.xyz,
                       vec3(0.0), last);
  const vec3 base = clamp(floor(g), vec3(0.0), max(last - 1.0, vec3(0.0)));
  const vec3 t = clamp(g - base, 0.0, 1.0);
  const int res = int(probe_grid.visibility.x);
  const uint stride = uint(probe_grid.visibility.y);
  const float inv_range = 1.0 / probe_grid.visibility.z;
  const vec3 biased = world_pos + probe_grid.visibility.w * (0.2 * normal + 0.8 * to_viewer);
  const bool relocated = probe_moments[0] != 0u;
  vec3 upper = vec3(0.0);
  float sum_w = 0.0;
  for (int c = 0; c < 8; ++c) {
    const ivec3 o = ivec3(c & 1, (c >> 1) & 1, c >> 2);
    const ivec3 cell = min(ivec3(base) + o, counts - 1);
    const uint rec =
        PROBE_MOMENT_HEADER + uint(cell.x + counts.x * (cell.y + counts.y * cell.z)) * stride;
    // Where the probe traced from: its grid position plus its relocation offset.
    vec3 probe_pos = probe_grid.origin.xyz + vec3(cell) * probe_grid.cell_size.xyz;
    if (relocated) {
      const uint at = rec + uint(res * res);
      probe_pos += uintBitsToFloat(uvec3(probe_moments[at], probe_moments[at + 1u],
                                         probe_moments[at + 2u]));
    }
    const vec3 tri3 = mix(1.0 - t, t, vec3(o));
    float w = tri3.x * tri3.y * tri3.z;
    const vec3 to_probe = probe_pos - world_pos;
    const float len = length(to_probe);
    const float facing = len > 0.0 ? dot(to_probe / len, normal) : 1.0;
    float v = (facing + 1.0) * 0.5;
    v = v * v + 0.2;
    const vec3 from_probe = biased - probe_pos;
    const float r = length(from_probe);
    if (r > 0.0) {
      const uint texel = octahedral_texel(from_probe / r, uint(res));
      const vec2 m = unpackHalf2x16(probe_moments[rec + texel]);
      v *= probe_chebyshev(r * inv_range, m.x, m.y);
    }
    v = max(v, 1e-6);
    if (v < 0.2) v *= v * v * 25.0;
    w *= v;
    upper += w * vec3(o);
    sum_w += w;
  }
  const vec3 t_moved = sum_w > 0.0 ? upper / sum_w : t;
  float s[4 * PROBE_SH_TEXTURES];
  probe_fetch_slots(probe_uvw(base + t_moved), s);
  // All the weight went to inactive probes (their moments are empty): as without visibility.
  if (!(s[0] > 0.0)) return probe_interpolate_trilinear(world_pos, sh);
  const float w = s[0];
  const float inv_w = w > 0.0 ? 1.0 / w : 0.0;
  for (int i = 0; i < PROBE_SH_COEFFS; ++i)
    sh[i] = vec3(s[1 + 3 * i], s[2 + 3 * i], s[3 + 3 * i]) * inv_w;
  return w > 0.0;
}

// The interpolated radiance SH at world_pos, seen from a surface with unit normal `normal` and
// the unit direction to_viewer toward the eye (used only with visibility); false (and zeros)
// when every probe around it is inactive or invisible. Positions outside the grid are clamped.
bool probe_interpolate(vec3 world_pos, vec3 normal, vec3 to_viewer, out vec3 sh[PROBE_SH_COEFFS]) {
  if (probe_grid.visibility.x > 0.0)
    return probe_interpolate_visible(world_pos, normal, to_viewer, sh);
  return probe_interpolate_trilinear(world_pos, sh);
}

// sum_l band_scale[l] sum_m sh_lm Y_lm(dir): the SH convolved with a zonal kernel at dir.
vec3 probe_eval_convolved(vec3 sh[PROBE_SH_COEFFS], vec3 dir, float band_scale[5]) {
  float y[SH_MAX_COEFFS];
  sh_basis(normalize(dir), PROBE_SH_ORDER, y);
  vec3 sum = vec3(0.0);
  for (int i = 0; i < PROBE_SH_COEFFS; ++i) sum += band_scale[sh_band(i)] * y[i] * sh[i];
  return sum;
}

// Irradiance from interpolated radiance SH at unit normal n (Ramamoorthi-Hanrahan cosine lobe,
// as sh::irradiance), negative ringing clamped to 0.
vec3 probe_sh_irradiance(vec3 sh[PROBE_SH_COEFFS], vec3 n) {
  const float cosine_lobe[5] = float[5](PROBE_PI, 2.0 * PROBE_PI / 3.0, PROBE_PI / 4.0, 0.0,
                                        -PROBE_PI / 24.0);
  return max(probe_eval_convolved(sh, n, cosine_lobe), vec3(0.0));
}

// Irradiance E at world_pos on a surface with unit normal `normal`.
// The viewer is taken along the normal.
vec3 probe_irradiance(vec3 world_pos, vec3 normal) {
  vec3 sh[PROBE_SH_COEFFS];
  if (!probe_interpolate(world_pos, normal, normal, sh)) return vec3(0.0);
  return probe_sh_irradiance(sh, normal);
}

// GGX ZH band scales k_1..k_4 (band 0 is 1) at glTF roughness r: the same 4-point Lagrange
// interpolation of the same 65 nodes as sh::ggx_zh, so CPU and GPU agree to float rounding.
vec4 brdf_ggx_zh(float roughness) {
  const float x = clamp(roughness, 0.0, 1.0) * float(BRDF_GGX_ZH_NODES - 1);
  const int j0 = clamp(int(floor(x)) - 1, 0, BRDF_GGX_ZH_NODES - 4);
  vec4 k = vec4(0.0);
  for (int a = 0; a < 4; ++a) {
    float p = 1.0;
    for (int b = 0; b < 4; ++b)
      if (b != a) p *= (x - float(j0 + b)) / float(a - b);
    k += p * brdf_ggx_zh_nodes[j0 + a];
  }
  return min(k, vec4(1.0));
}

// Prefiltered radiance of the split sum from interpolated SH: the SH convolved with the GGX
// lobe of `roughness` (sh::ggx_specular), evaluated in the reflected direction, clamped >= 0.
vec3 probe_sh_specular(vec3 sh[PROBE_SH_COEFFS], vec3 reflected_dir, float roughness) {
  const vec4 k = brdf_ggx_zh(roughness);
  const float lobe[5] = float[5](1.0, k.x, k.y, k.z, k.w);
  return max(probe_eval_convolved(sh, reflected_dir, lobe), vec3(0.0));
}

// Normal and viewer are both taken along reflected_dir.
vec3 probe_specular(vec3 world_pos, vec3 reflected_dir, float roughness) {
  vec3 sh[PROBE_SH_COEFFS];
  if (!probe_interpolate(world_pos, reflected_dir, reflected_dir, sh)) return vec3(0.0);
  return probe_sh_specular(sh, reflected_dir, roughness);
}

// Both at once from one interpolation: half the texture fetches of calling probe_irradiance
// and probe_specular separately (7 instead of 14 at L2), for shaders that need both.
void probe_lighting(vec3 world_pos, vec3 normal, vec3 reflected_dir, float roughness,
                    out vec3 irradiance, out vec3 specular) {
  vec3 sh[PROBE_SH_COEFFS];
  irradiance = vec3(0.0);
  specular = vec3(0.0);
  if (!probe_interpolate(world_pos, normal, reflect(-reflected_dir, normal), sh)) return;
  irradiance = probe_sh_irradiance(sh, normal);
  specular = probe_sh_specular(sh, reflected_dir, roughness);
}

// Texture coordinate of node-aligned tables: value v in [0, 1] over `size` texels whose
// centres hold the nodes at v = 0, 1/(size-1), ..., 1.
vec2 brdf_node_uv(vec2 v, vec2 size) { return (clamp(v, 0.0, 1.0) * (size - 1.0) + 0.5) / size; }

// Split-sum environment BRDF: the specular reflectance under uniform light is
// F0 * dfg.x + dfg.y (BrdfTables: GGX, height-correlated Smith, Schlick, as trace::Bsdf).
// brdf_dfg_at takes the table's coordinate x = cbrt(n.v) itself, for a shader that has it.
vec2 brdf_dfg_at(float x, float roughness) {
  const vec2 size = vec2(textureSize(brdf_dfg_table, 0));
  return textureLod(brdf_dfg_table, brdf_node_uv(vec2(x, roughness), size), 0.0).xy;
}
vec2 brdf_dfg(float n_dot_v, float roughness) {
  return brdf_dfg_at(pow(clamp(n_dot_v, 0.0, 1.0), 1.0 / 3.0), roughness);
}

#endif  // DDISH_PROBE_LIGHTING_GLSL
