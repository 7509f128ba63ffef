// scripts/light_split.sh against this build: it puts each kind of light in its own term. A scene
// lit by the sky alone (an open sphere) has all of its light, render's and reference's, in the
// sky term; a lamp over a plane (nothing to interreflect with) has all of it in the direct term,
// where the two renderers agree (1.00 measured at 32x24, 32 spp, 4 frames; the bound 0.05 is
// the reference's noise at 32 spp with room to spare). Without a scene and camera the script
// prints its usage and exits 2.
#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cli_runner.h"

namespace {

struct Split {
  int status = -1;
  std::string out;
};

Split run_split(const std::string& args) {
  const std::string cmd = "SIZE=32x24 SPP=32 FRAMES=4 DDISH=" + cli::quote(DDISH_EXE) + " bash " +
                          cli::quote(std::string(DDISH_SOURCE_DIR) + "/scripts/light_split.sh") + " " + args +
                          " 2>/dev/null";
  Split s;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return s;
  char buf[4096];
  while (std::fgets(buf, sizeof buf, p)) s.out += buf;
  const int st = pclose(p);
  s.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return s;
}

// The row "| NAME | render | reference | ratio | tiles |" as its three numbers; ratio -1 for "-".
struct Term {
  double render = -1.0, reference = -1.0, ratio = -1.0;
};
Term term(const std::string& out, const std::string& name) {
  const std::size_t at = out.find("| " + name + " | ");
  Term t;
  if (at == std::string::npos) return t;
  std::istringstream in(out.substr(at + name.size() + 4));
  std::string bar, ratio;
  in >> t.render >> bar >> t.reference >> bar >> ratio;
  t.ratio = ratio == "-" ? -1.0 : std::stod(ratio);
  return t;
}

std::string scene(const char* name) { return cli::quote(std::string(DDISH_SOURCE_DIR) + "/scenes/" + name); }

TEST(LightSplitScript, EachLightIsInItsOwnTerm) {
  const Split sky = run_split(scene("open_sphere.gltf") + " -");
  ASSERT_EQ(sky.status, 0) << sky.out;
  for (const char* none : {"direct", "lights"}) {
    const Term t = term(sky.out, none);
    EXPECT_EQ(t.render, 0.0) << none << "\n" << sky.out;
    EXPECT_EQ(t.reference, 0.0) << none << "\n" << sky.out;
  }
  const Term s = term(sky.out, "sky");
  EXPECT_GT(s.reference, 0.1) << sky.out;
  EXPECT_NEAR(s.ratio, 1.0, 0.05) << sky.out;
  EXPECT_EQ(term(sky.out, "all").render, s.render) << sky.out;

  const Split lamp = run_split(scene("photometric_lamp.gltf") + " -");
  ASSERT_EQ(lamp.status, 0) << lamp.out;
  const Term d = term(lamp.out, "direct");
  EXPECT_GT(d.reference, 0.01) << lamp.out;
  EXPECT_NEAR(d.ratio, 1.0, 0.05) << lamp.out;
  for (const char* none : {"lights", "sky"}) {
    // The plane cannot light itself; the probes' L2 ringing could leave a trace below 1e-3.
    const Term t = term(lamp.out, none);
    EXPECT_GE(t.render, 0.0) << none << "\n" << lamp.out;  // -1: no such row
    EXPECT_LE(t.render, 1e-3) << none << "\n" << lamp.out;
    EXPECT_EQ(t.reference, 0.0) << none << "\n" << lamp.out;
  }
}

TEST(LightSplitScript, WithoutASceneItPrintsItsUsage) {
  const std::string cmd = "bash " + cli::quote(std::string(DDISH_SOURCE_DIR) + "/scripts/light_split.sh") + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string out;
  char buf[512];
  while (std::fgets(buf, sizeof buf, p)) out += buf;
  const int st = pclose(p);
  EXPECT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 2) << out;
  EXPECT_EQ(out.rfind("usage: bash scripts/light_split.sh SCENE CAMERA", 0), 0u) << out;
}

}  // namespace
