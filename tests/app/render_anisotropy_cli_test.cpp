// `ddish render --anisotropy N`: 0 (automatic), 1 (off) and explicit maxima render; a value
// outside 0..16 is one line with exit code 2 that names the option.
#include <algorithm>
#include <string>

#include "display_cli.h"

namespace {

using namespace display_cli;

class RenderAnisotropyCli : public Cli {};

TEST_F(RenderAnisotropyCli, ValidValuesRender) {
  for (const char* n : {"0", "1", "4"}) {
    Result r = run("render " + cornell() + " --width 16 --height 16 --probe-samples 8 --msaa 1 "
                   "--anisotropy " + n + " --out " + path(std::string("out") + n));
    EXPECT_EQ(r.code, 0) << n << ": " << r.err;
  }
}

TEST_F(RenderAnisotropyCli, OutOfRangeIsOneLineExitTwo) {
  for (const char* n : {"-1", "17"}) {
    Result r = run("render " + cornell() + " --anisotropy " + n + " --out " + path("out"));
    EXPECT_EQ(r.code, 2) << n << ": " << r.err;
    EXPECT_EQ(r.err.rfind("ddish: error: --anisotropy must be 0 (automatic", 0), 0u) << n << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << n << ": " << r.err;
  }
}

}  // namespace
