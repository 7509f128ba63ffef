// Direct light (punctual lights with shadow maps) and the SH probes' light at one surface point,
// for the glTF metallic-roughness BSDF (forward_main.glsl says which terms, as the path tracer
// has them). It takes the point, its view and its material's values as arguments and reads no
// stage input, so that a pass which reconstructs the surface by other means than interpolated
// varyings (a deferred or visibility-buffer pass, issue 20) evaluates exactly the same light.
// The includer declares set 0 (raster_common.glsl), the feature switches (forward_variant.glsl)
// and the probe set (probe_lighting.glsl) first.
#ifndef DDISH_SURFACE_LIGHTING_GLSL
#define DDISH_SURFACE_LIGHTING_GLSL

layout(set = 0, binding = 4) uniform sampler2DArrayShadow shadow_maps;
// E(mu, roughness) and dE/dF0 (a layer of any F0 has E + (F0 - 0.04) dE/dF0) over 32 roughness
// nodes and 32 cbrt(mu) nodes, in cells (raster::FrameResources::albedo_table): for roughness node
// r and cosine cell c, (E, dE/dF0) at cosine nodes c and c + 1, at r * kCosCells + c; then from
// kAverageCells, for roughness cell r, (E_avg, dE_avg/dF0) at roughness nodes r and r + 1. One
// vec4 load per bilinear step: on lavapipe each load from a storage buffer at a per-pixel index
// is a per-lane gather, and the float layout took four times as many.
layout(set = 0, binding = 5, std430) readonly buffer AlbedoTable { vec4 albedo_cells[]; };

const int kCosNodes = 32;
const int kRoughnessNodes = 32;
const int kCosCells = kCosNodes - 1;
const int kAverageCells = kRoughnessNodes * kCosCells;
const float kMinAlpha = 1e-3;
const float kPi = 3.14159265358979;
const float kSpecularAaKappa = 0.18;  // the largest alpha^2 the filter adds

// The table's roughness coordinate: uniform in log(alpha) from kMinAlpha (0) to 1 (1).
float roughness_coordinate(float roughness) {
  const float r = clamp(roughness, 0.0, 1.0);
  const float a = max(r * r, kMinAlpha);
  return 1.0 - log(a) / log(kMinAlpha);
}

void locate(float v, int nodes, out int i, out float t) {
  const float f = clamp(v, 0.0, 1.0) * float(nodes - 1);
  i = min(int(f), nodes - 2);
  t = f - float(i);
}

// The tables' cosine coordinate, cbrt(mu): computed once per cosine and shared by every table
// read at it. On lavapipe the table reads with their cube roots (seven of each per pixel before)
// were roughly a quarter of a Sponza view's shading time (446 against 588 ms of CPU per frame
// with them replaced by constants, one run on a loaded machine).
float cosine_coordinate(float mu) { return pow(clamp(mu, 0.0, 1.0), 1.0 / 3.0); }

// E(mu) and dE/dF0(mu) at the roughness slice (r, tr) and cosine coordinate x: the two tables
// share their index arithmetic.
vec2 table_pair(int r, float tr, float x) {
  int c;
  float tc;
  locate(x, kCosNodes, c, tc);
  const vec4 a = albedo_cells[r * kCosCells + c];
  const vec4 b = albedo_cells[(r + 1) * kCosCells + c];
  vec2 e0 = a.xy;
  e0 += tc * (a.zw - e0);
  vec2 e1 = b.xy;
  e1 += tc * (b.zw - e1);
  return e0 + tr * (e1 - e0);
}

// The material's dielectric layer per channel at cosine coordinate x:
// weight * (E + (F0 - 0.04) dE/dF0), as trace::Bsdf::layer.
vec3 material_layer(vec4 dielectric, int r, float tr, float x) {
  const vec2 e = table_pair(r, tr, x);
  return dielectric.w * (e.x + (dielectric.rgb - 0.04) * e.y);
}

float smith_s(float alpha2, float c) { return sqrt(c * c + alpha2 * max(0.0, 1.0 - c * c)); }

// Fraction of light reaching p from shadow layers [first, first + count): PCF over a 3x3
// grid of hardware-compared (bilinear where the device filters depth) taps.
float shadow_lookup(uint layer, vec3 p) {
  const ShadowLayer s = shadow_layers[layer];
  const vec4 clip = s.light_view_proj * vec4(p, 1.0);
  const vec3 ndc = clip.xyz / clip.w;
  const vec2 uv = ndc.xy * 0.5 + 0.5;
  const float ref = ndc.z - s.params.x;
  const float texel = frame.shadow_params.x * frame.shadow_params.y;
  float lit = 0.0;
  if (frame.shadow_params.z > 0.5 && frame.shadow_params.y == 1.0) {
    // Bilinear taps one texel apart weight, per axis, the four texels from i0 - 1 to i0 + 2
    // (i0 = floor(x), x = uv * size - 0.5, f = fract(x)) by 1 - f, 1, 1, f: the same sum as two
    // bilinear taps, one at i0 - 1 + 1 / (2 - f) scaled by 2 - f and one at i0 + 1 + f / (1 + f)
    // scaled by 1 + f. 4 taps instead of 9, the same texels and weights (up to the filter's
    // rounding); on lavapipe each comparison tap is a per-lane float-path fetch.
    const vec2 x = uv / frame.shadow_params.x - 0.5;
    const vec2 i0 = floor(x);
    const vec2 f = x - i0;
    const vec2 wa = 2.0 - f;
    const vec2 wb = 1.0 + f;
    const vec2 a = (i0 - 0.5 + 1.0 / wa) * frame.shadow_params.x;
    const vec2 b = (i0 + 1.5 + f / wb) * frame.shadow_params.x;
    lit = wa.x * wa.y * texture(shadow_maps, vec4(a.x, a.y, float(layer), ref)) +
          wb.x * wa.y * texture(shadow_maps, vec4(b.x, a.y, float(layer), ref)) +
          wa.x * wb.y * texture(shadow_maps, vec4(a.x, b.y, float(layer), ref)) +
          wb.x * wb.y * texture(shadow_maps, vec4(b.x, b.y, float(layer), ref));
    return lit / 9.0;
  }
  for (int y = -1; y <= 1; ++y)
    for (int x = -1; x <= 1; ++x)
      lit += texture(shadow_maps, vec4(uv + vec2(x, y) * texel, float(layer), ref));
  return lit / 9.0;
}

bool inside_layer(uint layer, vec3 p, float margin) {
  const vec4 clip = shadow_layers[layer].light_view_proj * vec4(p, 1.0);
  const vec3 ndc = clip.xyz / clip.w;
  return all(lessThan(abs(ndc.xy), vec2(1.0 - margin))) && ndc.z >= 0.0 && ndc.z <= 1.0;
}

float shadow(LightData light, vec3 p, vec3 n, vec3 wi) {
  if (!kShadows || light.spot_shadow.z < 0.0) return 1.0;
  const uint first = uint(light.spot_shadow.z);
  const uint count = uint(light.spot_shadow.w);
  uint layer = first;
  const uint type = uint(light.direction_type.w);
  if (type == kLightPoint) {
    // Cube faces in the order +X, -X, +Y, -Y, +Z, -Z: the major axis of light -> p.
    const vec3 d = p - light.position_range.xyz;
    const vec3 a = abs(d);
    if (a.x >= a.y && a.x >= a.z) layer += d.x >= 0.0 ? 0u : 1u;
    else if (a.y >= a.z) layer += d.y >= 0.0 ? 2u : 3u;
    else layer += d.z >= 0.0 ? 4u : 5u;
  } else if (type == kLightDirectional) {
    // The finest cascade that holds p (with a PCF margin); none: unshadowed beyond the last.
    uint chosen = first + count;
    for (uint i = first; i < first + count; ++i)
      if (inside_layer(i, p, 0.02)) { chosen = i; break; }
    if (chosen == first + count) return 1.0;
    layer = chosen;
  }
  // Offsetting along the normal, more at grazing light, removes acne without peter-panning.
  const float cos_l = clamp(dot(n, wi), 0.0, 1.0);
  // Perspective layers store the texel size at unit distance (params.z = 1).
  const vec4 params = shadow_layers[layer].params;
  const float texel = params.y * (params.z > 0.5 ? length(p - light.position_range.xyz) : 1.0);
  const vec3 offset_p = p + n * texel * (1.0 + 2.0 * (1.0 - cos_l));
  return shadow_lookup(layer, offset_p);
}

// Direct light and the probes' light at the world position `world` seen from views[view], for
// the shading normal n and the material's values (dielectric: the layer's F0 in rgb and its
// weight in w, MaterialData.dielectric). It reads no material texture (the caller does, for
// the whole quad: their level comes from derivatives), so it may run under the prepass's
// visibility branch.
vec3 lighting(vec3 world, uint view, vec4 dielectric, vec3 n, vec3 albedo, float metallic,
              float roughness, float normal_variance, float occlusion) {
  const vec3 v = normalize(views[view].eye.xyz - world);
  const float nov = dot(n, v);
  // n.v for the tables, floored as the split sum needs it (a grazing 1e-4 changes no pixel).
  const float nv = max(clamp(nov, 0.0, 1.0), 1e-4);
  const float x_v = cosine_coordinate(nv);

  int r;
  float tr;
  locate(roughness_coordinate(roughness), kRoughnessNodes, r, tr);
  const vec4 avg = albedo_cells[kAverageCells + r];
  const float e_avg_0 = mix(avg.x, avg.z, tr);
  const float s_avg_0 = mix(avg.y, avg.w, tr);
  const vec3 e_avg = dielectric.w * (e_avg_0 + (dielectric.rgb - 0.04) * s_avg_0);
  const vec3 e_v = material_layer(dielectric, r, tr, x_v);
  const vec3 diffuse_lobe = (1.0 - metallic) * albedo / (kPi * (1.0 - e_avg)) * (1.0 - e_v);
  // The specular lobe's Fresnel f0 + f90_minus_f0 (1 - v.h)^5 (trace/bsdf.cpp): the dielectric
  // layer's Schlick term weighted by (1 - metallic) * weight, plus the metal's.
  const float dw = (1.0 - metallic) * dielectric.w;
  const vec3 spec_f0 = dw * dielectric.rgb + metallic * albedo;
  const vec3 spec_f90_minus_f0 = dw * (1.0 - dielectric.rgb) + metallic * (1.0 - albedo);
  const float alpha = max(roughness * roughness, kMinAlpha);
  // Geometric specular antialiasing for the punctual lights (Tokuyoshi and Kaplanyan 2021,
  // "Stable Geometric Specular Antialiasing with Projected-Space NDF Filtering"): the shader runs
  // once per pixel, but the path tracer's pixel is the BSDF averaged over the pixel's footprint.
  // Where the normal turns across the pixel (curved surfaces), a delta light's highlight from a
  // low-roughness lobe is far narrower than a pixel, and a point sample at its peak overshoots
  // the pixel average many times (Breakfast room teapot: 183 against the reference's 20). The
  // normal's screen-space variance widens the lobe: alpha^2 += min(2 sigma^2, kappa), with
  // sigma^2 = (|dn/dx|^2 + |dn/dy|^2) / (2 pi) of the interpolated vertex normal (taken at the
  // top of main(), before a masked material's discard). Flat surfaces (dn = 0) are unchanged.
  const float alpha2 = min(alpha * alpha + min(2.0 * normal_variance, kSpecularAaKappa), 1.0);

  vec3 color = vec3(0.0);
  if (kDirectLights && nov > 0.0) {
    for (uint i = 0u; i < frame.counts.x; ++i) {
      const LightData light = lights[i];
      const uint type = uint(light.direction_type.w);
      vec3 wi;
      vec3 radiance = light.radiant.rgb;
      if (type == kLightDirectional) {
        wi = -light.direction_type.xyz;
      } else {
        const vec3 d = light.position_range.xyz - world;
        const float dist2 = dot(d, d);
        if (!(dist2 > 0.0)) continue;
        const float dist = sqrt(dist2);
        wi = d / dist;
        float atten = 1.0 / dist2;
        const float range = light.position_range.w;
        if (range > 0.0) {
          const float q = dist / range;
          atten *= clamp(1.0 - q * q * q * q, 0.0, 1.0);
        }
        if (type == kLightSpot) {
          const float cd = dot(light.direction_type.xyz, -wi);
          const float a = clamp(cd * light.spot_shadow.x + light.spot_shadow.y, 0.0, 1.0);
          atten *= a * a;
        }
        radiance *= atten;
      }
      const float nol = dot(n, wi);
      if (nol <= 0.0 || !any(greaterThan(radiance, vec3(0.0)))) continue;
      const vec3 h = normalize(v + wi);
      const float noh = dot(n, h);
      const float voh = 0.5 * (dot(v, h) + dot(wi, h));
      // D with sin^2 from the tangent plane, V in the cancelled form (no 1 / cos).
      const float sin2 = max(0.0, 1.0 - noh * noh);
      const float tt = sin2 / alpha2 + noh * noh;
      const float d_ggx = noh > 0.0 ? 1.0 / (kPi * alpha2 * tt * tt) : 0.0;
      const float vis = 1.0 / (2.0 * (smith_s(alpha2, nov) * nol + smith_s(alpha2, nol) * nov));
      const float m = 1.0 - clamp(voh, 0.0, 1.0);
      const vec3 fresnel = spec_f0 + spec_f90_minus_f0 * (m * m * m * m * m);
      const vec3 f = diffuse_lobe * (1.0 - material_layer(dielectric, r, tr, cosine_coordinate(nol))) +
                     fresnel * (d_ggx * vis);
      color += f * radiance * nol * shadow(light, world, n, wi);
    }
  }

  if (kProbes) {
    // 1 - E(n.v) of the material's layer: the factor by which the tracer's albedo-scaled
    // diffuse lobe under uniform light differs from Lambert (the cosine-weighted mean of its
    // (1 - E(n.l)) / (1 - E_avg) factor is 1 by construction).
    const vec3 diffuse_scale = 1.0 - e_v;
    // One interpolation of the probes for both terms.
    vec3 sh[PROBE_SH_COEFFS];
    if (probe_interpolate(world, n, v, sh)) {
      color += albedo * (1.0 - metallic) * diffuse_scale / kPi * probe_sh_irradiance(sh, n) * occlusion;
      if (kSpecularProbes) {
        // The split sum of f0 + f90_minus_f0 w: f0 (dfg.x + dfg.y) + f90_minus_f0 dfg.y, which
        // is F0 dfg.x + dfg.y for Schlick.
        const vec2 dfg = brdf_dfg_at(x_v, roughness);
        color += (spec_f0 * (dfg.x + dfg.y) + spec_f90_minus_f0 * dfg.y) *
                 probe_sh_specular(sh, reflect(-v, n), roughness);
      }
    }
  }
  return color;
}

#endif
