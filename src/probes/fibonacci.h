// Probe ray directions: a spherical Fibonacci lattice (points on a golden-angle spiral with equal
// area per point), rotated by a fresh uniformly random rotation each update. The lattice
// integrates smooth functions far more accurately than independent random directions, and the
// rotation turns its fixed pattern into an unbiased estimate whose aliasing averages out over
// the updates of the running average.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "trace/sampler.h"

namespace ddish::probes {

// Direction i of an n-point spherical Fibonacci lattice (0 <= i < n): z evenly spaced in
// (-1, 1) at cell centres, azimuth advancing by the golden angle. Unit length.
glm::vec3 fibonacci_direction(std::uint32_t i, std::uint32_t n);

// A rotation drawn uniformly from SO(3) (Shoemake's unit-quaternion method) with three
// numbers from the sampler.
glm::mat3 random_rotation(trace::Sampler& sampler);

}  // namespace ddish::probes
