// libFuzzer target for the server's decoder of clients' view messages (net/view_message.h): any
// byte string is either refused with a reason or gives 1..256 views of a valid size with finite
// matrices, which re-encode to the same bytes. Seeds: tests/fuzz/corpus/view_message/.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "net/view_message.h"

using fuzz::require;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace ddish;
  std::vector<scene::View> views;
  std::string problem;
  if (!net::decode_views({data, size}, views, problem)) {
    require(!problem.empty() && views.empty());
    return 0;
  }
  require(!views.empty() && views.size() <= net::kMaxViewsPerClient);
  for (const scene::View& v : views) {
    require(v.width >= 1 && v.width <= 16384 && v.height >= 1 && v.height <= 16384);
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) require(std::isfinite(v.view[c][r]) && std::isfinite(v.projection[c][r]));
  }
  const std::vector<std::uint8_t> again = net::encode_views(views);
  require(again.size() == size && std::equal(again.begin(), again.end(), data));
  return 0;
}
