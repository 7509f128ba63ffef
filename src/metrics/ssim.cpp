#include "metrics/ssim.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "metrics/color.h"

namespace ddish::metrics {

namespace {

// Normalised 1D Gaussian taps for a window of `size` pixels centred on the window's middle
// (a half-integer for even sizes, so truncated windows stay symmetric).
std::vector<double> gaussian_taps(int size, double sigma) {
  std::vector<double> taps(static_cast<std::size_t>(size));
  const double centre = 0.5 * (size - 1);
  double sum = 0.0;
  for (int i = 0; i < size; ++i) {
    double d = i - centre;
    taps[static_cast<std::size_t>(i)] = std::exp(-d * d / (2.0 * sigma * sigma));
    sum += taps[static_cast<std::size_t>(i)];
  }
  for (double& t : taps) t /= sum;
  return taps;
}

// The five window moments SSIM needs, per window position.
struct Moments {
  double a = 0, b = 0, aa = 0, bb = 0, ab = 0;
  void add(double w, double va, double vb) {
    a += w * va;
    b += w * vb;
    aa += w * va * va;
    bb += w * vb * vb;
    ab += w * va * vb;
  }
  void add(double w, const Moments& m) {
    a += w * m.a;
    b += w * m.b;
    aa += w * m.aa;
    bb += w * m.bb;
    ab += w * m.ab;
  }
};

std::vector<double> display_luminance(const Image& image) {
  std::vector<double> y;
  y.reserve(image.pixel_count());
  for (const glm::vec3& p : image.pixels()) y.push_back(luminance(display_value(p)));
  return y;
}

}  // namespace

double ssim(const Image& image, const Image& reference, const SsimParams& params) {
  require_same_size(image, reference);
  if (image.empty()) throw std::invalid_argument("SSIM of an empty image");
  if (params.window < 1 || params.sigma <= 0.0)
    throw std::invalid_argument("SSIM window must be at least 1 pixel with sigma > 0");

  const int w = image.width();
  const int h = image.height();
  const int kx = std::min(params.window, w);
  const int ky = std::min(params.window, h);
  const std::vector<double> tx = gaussian_taps(kx, params.sigma);
  const std::vector<double> ty = gaussian_taps(ky, params.sigma);
  const std::vector<double> la = display_luminance(image);
  const std::vector<double> lb = display_luminance(reference);

  // The 2D Gaussian is separable: filter rows first (horizontal moments at each valid x), then
  // columns over those, which costs O(W H (kx + ky)) instead of O(W H kx ky).
  const int ox = w - kx + 1;  // valid positions along x
  const int oy = h - ky + 1;
  std::vector<Moments> rows(static_cast<std::size_t>(ox) * static_cast<std::size_t>(h));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < ox; ++x) {
      Moments m;
      for (int i = 0; i < kx; ++i) {
        std::size_t p = static_cast<std::size_t>(y) * static_cast<std::size_t>(w) +
                        static_cast<std::size_t>(x + i);
        m.add(tx[static_cast<std::size_t>(i)], la[p], lb[p]);
      }
      rows[static_cast<std::size_t>(y) * static_cast<std::size_t>(ox) +
           static_cast<std::size_t>(x)] = m;
    }
  }

  const double c1 = (params.k1 * params.range) * (params.k1 * params.range);
  const double c2 = (params.k2 * params.range) * (params.k2 * params.range);
  double total = 0.0;
  for (int y = 0; y < oy; ++y) {
    for (int x = 0; x < ox; ++x) {
      Moments m;
      for (int j = 0; j < ky; ++j)
        m.add(ty[static_cast<std::size_t>(j)],
              rows[static_cast<std::size_t>(y + j) * static_cast<std::size_t>(ox) +
                   static_cast<std::size_t>(x)]);
      const double var_a = m.aa - m.a * m.a;
      const double var_b = m.bb - m.b * m.b;
      const double cov = m.ab - m.a * m.b;
      total += ((2.0 * m.a * m.b + c1) * (2.0 * cov + c2)) /
               ((m.a * m.a + m.b * m.b + c1) * (var_a + var_b + c2));
    }
  }
  return total / (static_cast<double>(ox) * static_cast<double>(oy));
}

}  // namespace ddish::metrics
