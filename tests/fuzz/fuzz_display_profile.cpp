// Display profiles (displays/*.json) through the parser, then the view set the profile makes
// from a plain camera (rig, quilt layout, projections), as `ddish render --display FILE` does.
#include "display/profile.h"
#include "display/profile_views.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::accepts([&] {
    const ddish::display::Profile p =
        ddish::display::parse_profile(fuzz::as_text(data, size), "input.json");
    // Profiles may have up to a million views; a view set that big is legal and only costs
    // memory (about 0.3 KB a view), which would trip the fuzzer's memory limit, not a bug.
    if (p.views > 4096) return;
    const ddish::display::ViewSet set = ddish::display::make_view_set(p, {});
    if (set.size() != static_cast<std::size_t>(p.views))
      fuzz::finding("view set size differs from the profile's views", p.name.c_str());
  });
  return 0;
}
