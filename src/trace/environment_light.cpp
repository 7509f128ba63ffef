#include "trace/environment_light.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "scene/environment_map.h"
#include "trace/sampling.h"

namespace ddish::trace {

namespace {

double luminance(const glm::vec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

// Index i with cdf[i] <= u < cdf[i + 1] among the n bins of a normalised cdf (n + 1 entries),
// skipping empty bins, and the fraction of u within it.
int pick(const double* cdf, int n, double u, double& fraction) {
  const double* it = std::upper_bound(cdf, cdf + n + 1, u);
  int i = static_cast<int>(it - cdf) - 1;
  i = std::clamp(i, 0, n - 1);
  while (i > 0 && cdf[i + 1] <= cdf[i]) --i;  // landed in an empty bin at the top: step back
  const double width = cdf[i + 1] - cdf[i];
  fraction = width > 0.0 ? std::clamp((u - cdf[i]) / width, 0.0, 1.0) : 0.5;
  return i;
}

}  // namespace

EnvironmentLight::EnvironmentLight(std::shared_ptr<const scene::EnvironmentMap> map)
    : map_(std::move(map)), width_(map_->width), height_(map_->height) {
  const auto w = static_cast<std::size_t>(width_);
  const auto h = static_cast<std::size_t>(height_);
  weights_.assign(w * h, 0.0);
  row_sums_.assign(h, 0.0);
  col_cdf_.assign(h * (w + 1), 0.0);
  row_cdf_.assign(h + 1, 0.0);
  for (int y = 0; y < height_; ++y) {
    const double s = std::sin(std::numbers::pi * (y + 0.5) / height_);
    double* cdf = &col_cdf_[static_cast<std::size_t>(y) * (w + 1)];
    double sum = 0.0;
    for (int x = 0; x < width_; ++x) {
      const double wt = luminance(map_->texel(x, y)) * s;
      weights_[static_cast<std::size_t>(y) * w + static_cast<std::size_t>(x)] = wt;
      sum += wt;
      cdf[x + 1] = sum;
    }
    for (int x = 1; x <= width_; ++x) cdf[x] = sum > 0.0 ? cdf[x] / sum : double(x) / width_;
    row_sums_[static_cast<std::size_t>(y)] = sum;
    row_cdf_[static_cast<std::size_t>(y) + 1] = row_cdf_[static_cast<std::size_t>(y)] + sum;
  }
  total_ = row_cdf_[h];
  if (total_ > 0.0)
    for (double& c : row_cdf_) c /= total_;
}

bool EnvironmentLight::sample(const glm::vec2& u, EnvironmentSample& out) const {
  if (empty()) return false;
  double fy = 0.0;
  const int y = pick(row_cdf_.data(), height_, u.y, fy);
  double fx = 0.0;
  const int x = pick(&col_cdf_[static_cast<std::size_t>(y) * (static_cast<std::size_t>(width_) + 1)],
                     width_, u.x, fx);
  const glm::vec2 uv{static_cast<float>((x + fx) / width_), static_cast<float>((y + fy) / height_)};
  const float sin_theta = std::sin(uv.y * kPi);
  if (!(sin_theta > 0.0f)) return false;
  const double p_uv = weights_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                               static_cast<std::size_t>(x)] *
                      width_ * height_ / total_;
  if (!(p_uv > 0.0)) return false;
  out.wi = map_->direction_of(uv);
  out.pdf = static_cast<float>(p_uv / (2.0 * kPi * kPi * sin_theta));
  out.radiance = map_->radiance(out.wi);
  return true;
}

float EnvironmentLight::pdf(const glm::vec3& wi) const {
  if (empty()) return 0.0f;
  const glm::vec2 uv = map_->uv_of(wi);
  const int x = std::clamp(static_cast<int>(uv.x * width_), 0, width_ - 1);
  const int y = std::clamp(static_cast<int>(uv.y * height_), 0, height_ - 1);
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - wi.y * wi.y));
  if (!(sin_theta > 0.0f)) return 0.0f;
  const double p_uv = weights_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                               static_cast<std::size_t>(x)] *
                      width_ * height_ / total_;
  return static_cast<float>(p_uv / (2.0 * kPi * kPi * sin_theta));
}

glm::vec3 EnvironmentLight::radiance(const glm::vec3& wi) const { return map_->radiance(wi); }

double EnvironmentLight::texel_probability(int x, int y) const {
  if (empty()) return 0.0;
  return weights_[static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) +
                  static_cast<std::size_t>(x)] /
         total_;
}

}  // namespace ddish::trace
