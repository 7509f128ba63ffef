#include "trace/ray_recorder.h"

namespace ddish::trace {

std::vector<RecordedRay> RayRecorder::take() {
  std::vector<RecordedRay> all;
  std::size_t n = 0;
  for (const std::vector<RecordedRay>& list : lists_) n += list.size();
  all.reserve(n);
  for (std::vector<RecordedRay>& list : lists_) {
    all.insert(all.end(), list.begin(), list.end());
    list.clear();
  }
  return all;
}

}  // namespace ddish::trace
