// Probe classification: is a probe inside geometry? A probe in open space sees the front of
// every surface around it; a probe inside a closed mesh, or buried in a wall, sees the back of
// single-sided surfaces. The probe tracer counts back-face first hits among a probe's rays on
// its first update, and a probe whose fraction exceeds the threshold is made inactive: it is
// not traced again and interpolation gives it zero weight, so the light inside a wall (black,
// or light leaking through the backs of faces) never bleeds onto the surfaces next to it.
//
// Threshold 0.25 (the back-face fraction above which a probe is inside): a probe strictly
// inside a closed mesh (a pillar, a floor slab) scores 1.0, one behind a single-sided wall that
// closes off half its sphere about 0.5, and one in open space 0. Open scenes built of
// single-sided geometry put some back faces in view of probes that are usefully placed (the
// back of a facade or an eave seen from outside); allowing up to a quarter of the sphere keeps
// those, while a probe that sees the inside of something over more than a quarter of its
// sphere would give the visible surfaces next to it the wrong light.
#pragma once

#include <cstdint>

namespace ddish::probes {

inline constexpr float kInsideBackfaceFraction = 0.25f;

struct Classification {
  float backface_fraction = 0.0f;
  bool inside_geometry = false;
};

// rays > 0; threshold in [0, 1].
Classification classify(std::uint32_t backface_hits, std::uint32_t rays,
                        float threshold = kInsideBackfaceFraction);

}  // namespace ddish::probes
