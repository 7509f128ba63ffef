// The glTF metallic-roughness BSDF of src/trace/bsdf.h in GLSL, for the GPU probe tracer
// (src/trace_vk): Lambert base coupled to a GGX specular layer by albedo scaling (energy
// conserving), height-correlated Smith visibility, Schlick Fresnel, sampling of visible normals
// with the one-sample lobe mixture. src/trace/bsdf.cpp and ggx.h explain every formula; this file
// must follow them. Directions are in the local shading frame (z = shading normal).
//
// The includer declares, before including this file, the dielectric layer's albedo table of
// trace::DielectricSpecularAlbedo as ALBEDO_E(i), ALBEDO_S(i) (32 x 32, row = roughness node) and
// ALBEDO_E_AVG(r), ALBEDO_S_AVG(r).
#ifndef DDISH_TRACE_BSDF_GLSL
#define DDISH_TRACE_BSDF_GLSL

const float PI = 3.14159265358979;
const float INV_PI = 0.31830988618379067;
const float GGX_MIN_ALPHA = 1e-3;
const float DIELECTRIC_F0 = 0.04;
const int ALBEDO_NODES = 32;  // cosine and roughness nodes alike

float ggx_alpha(float roughness) {
  const float r = clamp(roughness, 0.0, 1.0);
  return max(r * r, GGX_MIN_ALPHA);
}

float ggx_d(float alpha2, vec3 h) {
  if (h.z <= 0.0) return 0.0;
  const float t = (h.x * h.x + h.y * h.y) / alpha2 + h.z * h.z;
  return 1.0 / (PI * alpha2 * t * t);
}

float ggx_smith_s(float alpha2, vec3 w) {
  return sqrt(w.z * w.z + alpha2 * max(0.0, w.x * w.x + w.y * w.y));
}

float ggx_visibility(float alpha2, vec3 wo, vec3 wi) {
  const float denom = 2.0 * (ggx_smith_s(alpha2, wo) * abs(wi.z) + ggx_smith_s(alpha2, wi) * abs(wo.z));
  return denom > 0.0 ? 1.0 / denom : 0.0;
}

vec3 ggx_sample_visible_normal(float alpha, vec3 wo, vec2 u) {
  const vec3 v = normalize(vec3(alpha * wo.x, alpha * wo.y, wo.z));
  const float phi = 2.0 * PI * u.x;
  const float z = (1.0 - u.y) * (1.0 + v.z) - v.z;
  const float sin_theta = sqrt(clamp(1.0 - z * z, 0.0, 1.0));
  const vec3 hs = vec3(sin_theta * cos(phi), sin_theta * sin(phi), z) + v;
  const vec3 h = vec3(alpha * hs.x, alpha * hs.y, max(hs.z, 0.0));
  const float len2 = dot(h, h);
  return len2 > 1e-30 ? h / sqrt(len2) : vec3(0.0, 0.0, 1.0);
}

float ggx_reflected_pdf(float alpha2, vec3 wo, vec3 h) {
  if (wo.z <= 0.0) return 0.0;
  return ggx_d(alpha2, h) / (2.0 * (wo.z + ggx_smith_s(alpha2, wo)));
}

// Concentric disk, then Malley's lift: cosine-weighted hemisphere (trace/sampling.h).
vec3 sample_cosine_hemisphere(vec2 u) {
  const float a = 2.0 * u.x - 1.0;
  const float b = 2.0 * u.y - 1.0;
  vec2 d = vec2(0.0);
  if (a != 0.0 || b != 0.0) {
    float r, phi;
    if (abs(a) > abs(b)) {
      r = a;
      phi = (PI / 4.0) * (b / a);
    } else {
      r = b;
      phi = (PI / 2.0) - (PI / 4.0) * (a / b);
    }
    d = vec2(r * cos(phi), r * sin(phi));
  }
  return vec3(d, sqrt(max(0.0, 1.0 - dot(d, d))));
}

float schlick_weight(float cos_theta) {
  const float m = 1.0 - clamp(cos_theta, 0.0, 1.0);
  const float m2 = m * m;
  return m2 * m2 * m;
}

float mean3(vec3 v) { return (v.x + v.y + v.z) * (1.0 / 3.0); }

// Position of v in a uniform grid of ALBEDO_NODES over [0, 1]: lower node and fraction.
void albedo_locate(float v, out int i, out float t) {
  const float f = clamp(v, 0.0, 1.0) * float(ALBEDO_NODES - 1);
  i = min(int(f), ALBEDO_NODES - 2);
  t = f - float(i);
}

struct Bsdf {
  vec3 base;
  float metallic;
  vec3 df0;  // the dielectric layer's F0
  float specular;
  vec3 f0;
  float alpha;
  vec3 f90_minus_f0;
  float diffuse_weight;
  vec3 diffuse;
  float row_t;  // the roughness row and its fraction in the albedo table
  int row;
};

Bsdf make_bsdf(vec3 base, float metallic, float roughness, vec3 df0, float specular) {
  Bsdf b;
  b.base = clamp(base, vec3(0.0), vec3(1.0));
  b.metallic = clamp(metallic, 0.0, 1.0);
  roughness = clamp(roughness, 0.0, 1.0);
  b.df0 = clamp(df0, vec3(0.0), vec3(1.0));
  b.specular = clamp(specular, 0.0, 1.0);
  b.alpha = ggx_alpha(roughness);
  const float dielectric = 1.0 - b.metallic;
  b.f0 = dielectric * b.specular * b.df0 + b.metallic * b.base;
  b.f90_minus_f0 = dielectric * b.specular * (1.0 - b.df0) + b.metallic * (1.0 - b.base);
  // The table's roughness coordinate: uniform in log(alpha) from GGX_MIN_ALPHA (0) to 1 (1).
  albedo_locate(1.0 - log(b.alpha) / log(GGX_MIN_ALPHA), b.row, b.row_t);
  const float e_avg = mix(ALBEDO_E_AVG(b.row), ALBEDO_E_AVG(b.row + 1), b.row_t);
  const float s_avg = mix(ALBEDO_S_AVG(b.row), ALBEDO_S_AVG(b.row + 1), b.row_t);
  const vec3 layer_avg = b.specular * (e_avg + (b.df0 - DIELECTRIC_F0) * s_avg);
  b.diffuse = dielectric * b.base * INV_PI / (1.0 - layer_avg);
  b.diffuse_weight = dielectric * mean3(b.base);
  return b;
}

// The dielectric layer's directional albedo per channel at cos_theta.
vec3 bsdf_layer(Bsdf b, float cos_theta) {
  int c;
  float tc;
  albedo_locate(pow(clamp(cos_theta, 0.0, 1.0), 1.0 / 3.0), c, tc);
  const int i0 = b.row * ALBEDO_NODES + c;
  const int i1 = i0 + ALBEDO_NODES;
  const float e = mix(mix(ALBEDO_E(i0), ALBEDO_E(i0 + 1), tc), mix(ALBEDO_E(i1), ALBEDO_E(i1 + 1), tc), b.row_t);
  const float s = mix(mix(ALBEDO_S(i0), ALBEDO_S(i0 + 1), tc), mix(ALBEDO_S(i1), ALBEDO_S(i1 + 1), tc), b.row_t);
  return b.specular * (e + (b.df0 - DIELECTRIC_F0) * s);
}

vec3 bsdf_eval(Bsdf b, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return vec3(0.0);
  const vec3 diffuse = b.diffuse * (1.0 - bsdf_layer(b, wo.z)) * (1.0 - bsdf_layer(b, wi.z));
  const float alpha2 = b.alpha * b.alpha;
  const vec3 h = normalize(wo + wi);
  const float cos_h = 0.5 * (dot(wo, h) + dot(wi, h));
  const vec3 fresnel = b.f0 + b.f90_minus_f0 * schlick_weight(cos_h);
  return diffuse + fresnel * (ggx_d(alpha2, h) * ggx_visibility(alpha2, wo, wi));
}

float bsdf_specular_probability(Bsdf b, vec3 wo) {
  const float e = mean3(bsdf_layer(b, wo.z));
  const vec3 metal_fresnel = b.base + (1.0 - b.base) * schlick_weight(wo.z);
  const float specular = (1.0 - b.metallic) * e + b.metallic * mean3(metal_fresnel);
  const float diffuse = b.diffuse_weight * (1.0 - e);
  const float total = specular + diffuse;
  return total > 0.0 ? specular / total : 1.0;
}

float bsdf_mixture_pdf(Bsdf b, vec3 wo, vec3 wi, float p_specular) {
  const vec3 h = normalize(wo + wi);
  const float pdf_specular = ggx_reflected_pdf(b.alpha * b.alpha, wo, h);
  return p_specular * pdf_specular + (1.0 - p_specular) * max(wi.z, 0.0) * INV_PI;
}

float bsdf_pdf(Bsdf b, vec3 wo, vec3 wi) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return 0.0;
  return bsdf_mixture_pdf(b, wo, wi, bsdf_specular_probability(b, wo));
}

// Samples wi from u (u.x picks the lobe); false when no direction was produced.
bool bsdf_sample(Bsdf b, vec3 wo, vec3 u, out vec3 wi, out vec3 weight, out float pdf) {
  wi = vec3(0.0);
  weight = vec3(0.0);
  pdf = 0.0;
  if (wo.z <= 0.0) return false;
  const float p_specular = bsdf_specular_probability(b, wo);
  if (u.x < p_specular) {
    const vec3 h = ggx_sample_visible_normal(b.alpha, wo, u.yz);
    wi = 2.0 * dot(wo, h) * h - wo;
  } else {
    wi = sample_cosine_hemisphere(u.yz);
  }
  if (wi.z <= 0.0) return false;
  wi = normalize(wi);
  pdf = bsdf_mixture_pdf(b, wo, wi, p_specular);
  if (!(pdf > 0.0)) return false;
  weight = bsdf_eval(b, wo, wi) * (wi.z / pdf);
  return true;
}

#endif  // DDISH_TRACE_BSDF_GLSL
