#include "probes/priority.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "probes/frustum.h"

namespace ddish::probes {

void check_priority_options(const PriorityOptions& options) {
  if (!(options.margin >= 0.0f) || !std::isfinite(options.margin))
    throw std::invalid_argument("frustum margin must be >= 0 metres, got " +
                                std::to_string(options.margin));
  if (options.max_age == 0) throw std::invalid_argument("maximum probe age must be at least 1");
  if (!(options.reference_pixels > 0.0f) || !std::isfinite(options.reference_pixels))
    throw std::invalid_argument("reference pixels must be > 0, got " +
                                std::to_string(options.reference_pixels));
}

namespace {

// What one view needs per probe: its frustum, eye, and how many pixels a cell of the grid
// covers at a given distance.
struct ViewInfo {
  Frustum frustum;
  glm::vec3 eye{0.0f};
  bool perspective = true;
  float pixels_per_radian = 0.0f;  // perspective: 1 / pixel angle at the image centre
  float pixels_per_metre = 0.0f;   // orthographic
};

ViewInfo view_info(const scene::View& v) {
  if (v.height <= 0)
    throw std::invalid_argument("view '" + v.name + "' has no pixels (height " +
                                std::to_string(v.height) + ")");
  ViewInfo info;
  info.frustum = Frustum(v);
  info.eye = v.eye();
  // |P11| = 2 n / (top - bottom) for a perspective (also off-axis) frustum: the image spans
  // 2 / |P11| in tan(angle) over its height. An orthographic projection has w = 1 everywhere
  // (no z term in the clip w row) and spans 2 / |P11| metres.
  const float p11 = std::abs(v.projection[1][1]);
  info.perspective = v.projection[2][3] != 0.0f;
  info.pixels_per_radian = p11 * float(v.height) * 0.5f;
  info.pixels_per_metre = p11 * float(v.height) * 0.5f;
  return info;
}

}  // namespace

ProbePriorities compute_priorities(const ProbeVolume& volume, std::span<const scene::View> views,
                                   const PriorityOptions& options) {
  check_priority_options(options);
  std::vector<ViewInfo> infos;
  infos.reserve(views.size());
  for (const scene::View& v : views) infos.push_back(view_info(v));

  const ProbeGrid& grid = volume.grid();
  const glm::vec3 spacing = grid.spacing();
  const float cell = std::max({spacing.x, spacing.y, spacing.z});
  const float max_age = float(options.max_age);

  const std::uint32_t n = volume.probe_count();
  ProbePriorities out;
  out.priority.assign(n, ProbePriority{});
  out.candidate.assign(n, 0);
  out.in_view.assign(n, 0);
  out.pixels.assign(n, 0.0f);

  for (std::uint32_t i = 0; i < n; ++i) {
    const ProbeState& s = volume.state(i);
    if (!s.active()) continue;
    out.candidate[i] = 1;
    ++out.active;

    const glm::vec3 p = grid.position(i);
    const scene::Aabb influence{p - spacing, p + spacing};
    bool seen = false;
    float pixels = 0.0f;
    for (const ViewInfo& v : infos) {
      if (!v.frustum.intersects(influence, options.margin)) continue;
      seen = true;
      float px = 0.0f;
      if (v.perspective) {
        const float distance = std::max(glm::length(p - v.eye), cell);
        px = distance > 0.0f ? cell / distance * v.pixels_per_radian : 0.0f;
      } else {
        px = cell * v.pixels_per_metre;
      }
      pixels = std::max(pixels, px);
    }
    out.in_view[i] = seen ? 1 : 0;
    out.pixels[i] = pixels;
    if (seen) ++out.in_view_count;

    const float importance = seen ? 1.0f + pixels / options.reference_pixels : 1.0f / max_age;
    ProbePriority& pr = out.priority[i];
    if (s.age >= options.max_age) {
      pr = {2, float(s.age)};
      ++out.overdue;
    } else if (s.updates == 0) {
      pr = {1, importance};
      ++out.fresh;
    } else {
      pr = {0, (float(s.age) + 1.0f) * importance};
    }
  }
  return out;
}

}  // namespace ddish::probes
