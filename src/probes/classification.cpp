#include "probes/classification.h"

namespace ddish::probes {

Classification classify(std::uint32_t backface_hits, std::uint32_t rays, float threshold) {
  Classification c;
  if (rays == 0) return c;  // nothing seen, nothing to conclude: the probe stays active
  c.backface_fraction = float(backface_hits) / float(rays);
  c.inside_geometry = c.backface_fraction > threshold;
  return c;
}

}  // namespace ddish::probes
