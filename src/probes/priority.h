// Probe priorities from all views at once: which probes a frame should update first.
//
// A probe's light is interpolated into the 8 cells around it, so what it influences is the box
// of +-1 spacing around its position. For every view, that box is tested against the view's
// frustum widened by `margin` metres (frustum.h); the probe is "in view" when it meets any.
// Its detail is the largest projected size of a cell in any view that sees it, in pixels:
//   pixels_v = cell / max(distance_v, cell) / pixel_angle_v
// cell: the largest grid spacing; distance_v: eye to probe; pixel_angle_v = 2 / (|P11| height),
// the angle one pixel spans at the image centre (for an orthographic view: cell |P11| height / 2).
// The max(distance, cell) bound keeps a probe at the eye finite (one cell seen from one cell
// away is already as large as the influence of a probe can look).
//
// From detail and age (ProbeState::age, updates missed since its last one), in three tiers,
// a higher tier always first:
//   2 overdue: age >= max_age, or never updated while max_age has passed; value = age. These
//      must be updated now, so that no active probe's age exceeds max_age (turning the head
//      never uncovers light older than max_age frames).
//   1 fresh: never updated (a new or re-classified probe holds no light at all);
//      value = importance.
//   0 normal: value = (age + 1) * importance.
// importance = 1 + pixels / reference_pixels for a probe in view (>= 1, growing with its size on
// screen), 1 / max_age for one out of every view, so an unseen probe ranks with a just-updated
// barely visible one when it is about to become overdue. Ages multiply importance so that every
// probe's priority keeps growing until it is picked: no visible probe starves.
// Inactive probes have no priority at all (never scheduled, never traced).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "probes/probe_volume.h"
#include "scene/view.h"

namespace ddish::probes {

struct PriorityOptions {
  // Metres every frustum is widened by: about the distance the camera moves before a probe
  // updated now has been refreshed again (1 m/s over 0.5 s at the default budget rates).
  float margin = 0.5f;
  // Frames: a probe this old is updated whatever the views see (--max-age).
  std::uint32_t max_age = 30;
  // A cell this many pixels across doubles a probe's importance over a barely visible one.
  float reference_pixels = 32.0f;
};

// Throws std::invalid_argument for a negative or non-finite margin, max_age == 0 or
// reference_pixels <= 0.
void check_priority_options(const PriorityOptions& options);

struct ProbePriority {
  std::uint8_t tier = 0;  // 2 overdue, 1 fresh, 0 normal (see above)
  float value = 0.0f;     // order within the tier

  bool operator<(const ProbePriority& o) const {
    return tier != o.tier ? tier < o.tier : value < o.value;
  }
  bool operator>(const ProbePriority& o) const { return o < *this; }
};

struct ProbePriorities {
  std::vector<ProbePriority> priority;  // per probe; meaningful for candidates only
  std::vector<std::uint8_t> candidate;  // 1: active, may be scheduled
  std::vector<std::uint8_t> in_view;    // 1: meets a widened frustum
  std::vector<float> pixels;            // detail in pixels, 0 out of view
  std::uint32_t active = 0;
  std::uint32_t in_view_count = 0;  // active probes in view
  std::uint32_t overdue = 0;        // active probes in tier 2
  std::uint32_t fresh = 0;          // active probes in tier 1
};

// Throws std::invalid_argument (check_priority_options, or a view with no pixels).
ProbePriorities compute_priorities(const ProbeVolume& volume, std::span<const scene::View> views,
                                   const PriorityOptions& options);

}  // namespace ddish::probes
