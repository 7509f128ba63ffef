// Looking Glass calibration JSON (visual.json) through its parser and the lenticular mapping
// built from it.
#include "display/calibration.h"
#include "display/lenticular.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::accepts([&] {
    const ddish::display::Calibration c =
        ddish::display::parse_calibration(fuzz::as_text(data, size), "visual.json");
    ddish::display::lenticular_mapping(c);
  });
  return 0;
}
