#include "display/stereo.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

namespace ddish::display {

namespace {

constexpr float kQuarterTurn = 1.5707963f;

void validate_fov(const EyeFov& fov, const char* eye) {
  const bool ok = fov.left < fov.right && fov.down < fov.up && fov.left > -kQuarterTurn &&
                  fov.right < kQuarterTurn && fov.down > -kQuarterTurn && fov.up < kQuarterTurn;
  if (!ok) {
    throw std::invalid_argument(std::string(eye) +
                                " eye field of view needs -90° < left < right < 90° and "
                                "-90° < down < up < 90°");
  }
}

}  // namespace

void StereoParams::validate() const {
  if (!(ipd >= 0.0f) || !std::isfinite(ipd)) {
    throw std::invalid_argument("stereo IPD " + std::to_string(ipd) + " must be >= 0");
  }
  if (left_eye_fov.has_value() != right_eye_fov.has_value()) {
    throw std::invalid_argument("stereo field of view is given for one eye only");
  }
  if (left_eye_fov) validate_fov(*left_eye_fov, "left");
  if (right_eye_fov) validate_fov(*right_eye_fov, "right");
  if (convergence_distance && !(*convergence_distance > 0.0f)) {
    throw std::invalid_argument("stereo convergence distance must be positive");
  }
}

scene::View fov_view(const BaseCamera& base, float offset_right, const EyeFov& fov, int width,
                     int height) {
  const glm::vec3 f = base.axis_forward();
  const glm::vec3 u = base.axis_up();
  const glm::vec3 eye = base.eye + offset_right * base.axis_right();
  scene::View v;
  v.view = glm::lookAtRH(eye, eye + f, u);
  // The angles are measured from the eye's own axis, so the near-plane rectangle is simply
  // near · tan(angle) on each side.
  const float n = base.znear;
  v.projection = scene::frustum_vk(n * std::tan(fov.left), n * std::tan(fov.right),
                                   n * std::tan(fov.down), n * std::tan(fov.up), n, base.zfar);
  v.width = width;
  v.height = height;
  return v;
}

ViewSet stereo_views(const BaseCamera& base, const StereoParams& params, int eye_width,
                     int eye_height, float aspect) {
  base.validate();
  params.validate();
  ViewSet set;
  set.kind = ViewSetKind::Stereo;
  set.name = to_string(set.kind);
  set.layout = layout_from_tiles(2, 1, eye_width, eye_height);
  const float half_ipd = 0.5f * params.ipd;

  if (params.left_eye_fov) {
    const EyeFov& l = *params.left_eye_fov;
    set.aspect = (std::tan(l.right) - std::tan(l.left)) / (std::tan(l.up) - std::tan(l.down));
    set.views.push_back(fov_view(base, -half_ipd, l, eye_width, eye_height));
    set.views.push_back(fov_view(base, half_ipd, *params.right_eye_fov, eye_width, eye_height));
  } else {
    set.aspect = aspect > 0.0f ? aspect : float(eye_width) / float(eye_height);
    const float tan_half = std::tan(0.5f * base.fov_y);
    if (params.converge) {
      // Both eyes frame the base camera's rectangle at the convergence distance.
      const float d = params.convergence_distance.value_or(base.focal_distance);
      const float half_h = d * tan_half;
      for (float offset : {-half_ipd, half_ipd}) {
        set.views.push_back(sheared_view(base, offset, 0.0f, d, set.aspect * half_h, half_h,
                                         eye_width, eye_height));
      }
    } else {
      // Each eye's frustum is centred on its own axis: framing a rectangle that moves with the
      // eye is the same as shearing by nothing.
      const float d = base.focal_distance;
      const float half_h = d * tan_half;
      for (float offset : {-half_ipd, half_ipd}) {
        BaseCamera eye = base;
        eye.eye = base.eye + offset * base.axis_right();
        set.views.push_back(sheared_view(eye, 0.0f, 0.0f, d, set.aspect * half_h, half_h,
                                         eye_width, eye_height));
      }
    }
  }
  set.views[0].name = "left";
  set.views[1].name = "right";
  return set;
}

}  // namespace ddish::display
