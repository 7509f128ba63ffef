// The split-sum environment BRDF ("DFG" table) of the glTF specular lobe as trace::Bsdf
// evaluates it: GGX with alpha = roughness^2 (floored at trace::Ggx::kMinAlpha), the
// height-correlated Smith G2 and Schlick's Fresnel. Since Schlick's F is linear in F0,
//   integral f_spec(v, l) cos(l) dl = F0 * scale + bias,
//   scale = integral D V (1 - (1 - v.h)^5) cos(l) dl,   bias = integral D V (1 - v.h)^5 cos(l) dl,
// with V = G2 / (4 n.l n.v). A rasterizer multiplies F0 * scale + bias by the prefiltered
// radiance (probe_specular) to get the specular reflection of the probes' light.
#pragma once

#include <vector>

#include <glm/glm.hpp>

namespace ddish::raster {

// (scale, bias) at one n.v and roughness, by the midpoint rule over n x n samples of the GGX
// distribution of visible normals (trace::Ggx::sample_visible_normal), whose weight f cos / pdf
// reduces to F G2 / G1(v). n.v is clamped to [1e-6, 1], as in trace::DielectricSpecularAlbedo.
glm::vec2 integrate_dfg(float n_dot_v, float roughness, int n);

// The table: size x size nodes, node (i, j) at cbrt(n.v) = i / (size - 1) and roughness =
// j / (size - 1). The cube root crowds the nodes towards grazing angles, where scale and bias
// change fastest (as trace::DielectricSpecularAlbedo does); with nodes uniform in n.v the
// interpolation error at n.v = 0.02 was 0.028. Nodes lie at texel centres on the GPU, so
// bilinear filtering interpolates between them.
struct DfgTable {
  static constexpr int kDefaultSize = 32;
  static constexpr int kDefaultQuadrature = 64;  // 64 x 64 = 4096 samples per node

  int size = 0;
  std::vector<glm::vec2> values;  // node (i, j) at values[j * size + i]

  glm::vec2 node(int i, int j) const { return values[std::size_t(j * size + i)]; }
  // Bilinear interpolation between the nodes in (cbrt(n.v), roughness), as the GPU's sampler
  // does; both clamped to [0, 1].
  glm::vec2 lookup(float n_dot_v, float roughness) const;
};

// Computes every node with integrate_dfg(.., quadrature), rows in parallel (tens of ms at the
// defaults on one core; the table is made once per BrdfTables).
DfgTable compute_dfg_table(int size = DfgTable::kDefaultSize,
                           int quadrature = DfgTable::kDefaultQuadrature);

}  // namespace ddish::raster
