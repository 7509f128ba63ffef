#include "sh/projection.h"

#include <algorithm>

namespace ddish::sh {

void ShProjector::add(const glm::vec3& dir, const glm::vec3& value, float weight) {
  float y[kMaxCoeffs];
  eval_basis(dir, order_, y);
  const glm::dvec3 v = glm::dvec3(value) * double(weight);
  const int n = coeff_count(order_);
  for (int i = 0; i < n; ++i) sum_[static_cast<std::size_t>(i)] += v * double(y[i]);
  weight_sum_ += double(weight);
  ++n_;
}

void ShProjector::merge(const ShProjector& other) {
  order_ = std::max(order_, other.order_);
  for (std::size_t i = 0; i < sum_.size(); ++i) sum_[i] += other.sum_[i];
  weight_sum_ += other.weight_sum_;
  n_ += other.n_;
}

void ShProjector::reset() {
  sum_.fill(glm::dvec3(0.0));
  weight_sum_ = 0.0;
  n_ = 0;
}

ShRgb ShProjector::result() const {
  ShRgb r(order_);
  for (int i = 0; i < r.count(); ++i) r[i] = glm::vec3(sum_[static_cast<std::size_t>(i)]);
  return r;
}

ShRgb ShProjector::result_normalized() const {
  ShRgb r(order_);
  if (weight_sum_ <= 0.0) return r;
  const double s = double(kFourPi) / weight_sum_;
  for (int i = 0; i < r.count(); ++i) r[i] = glm::vec3(sum_[static_cast<std::size_t>(i)] * s);
  return r;
}

ShRgb project_direction(const glm::vec3& dir, const glm::vec3& value, int order) {
  ShRgb r(order);
  float y[kMaxCoeffs];
  eval_basis(dir, r.order, y);
  for (int i = 0; i < r.count(); ++i) r[i] = value * y[i];
  return r;
}

}  // namespace ddish::sh
