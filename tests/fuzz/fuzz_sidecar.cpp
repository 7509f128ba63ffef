// The sidecar NAME.ddish.json (environment, probe grid, default camera) through its parser.
#include "fuzz_support.h"
#include "scene/sidecar.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::accepts([&] { ddish::scene::parse_sidecar(fuzz::as_text(data, size), "input.ddish.json"); });
  return 0;
}
