// The command line as a new user meets it: an unknown command is named and refused (exit 2),
// with or without --help, and the help of the options whose meaning surprised people says what
// they mean: --bounces counts the first hit (1 is direct light only), compare takes the reference
// second and measures PSNR / SSIM on clamped sRGB values.
#include <string>

#include <gtest/gtest.h>

#include "cli_runner.h"

namespace {

using cli::Result;

class CommandLineCli : public cli::TempDirTest {
 protected:
  CommandLineCli() : TempDirTest("ddish_command_line_cli_") {}
};

// Exactly one line on stderr, with the prefix main() gives every user error, and exit code 2.
void expect_one_error_line(const Result& r, const std::string& must_contain) {
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(r.err.rfind("ddish: error: ", 0), 0u) << r.err;
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
  EXPECT_NE(r.err.find(must_contain), std::string::npos) << r.err;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST_F(CommandLineCli, UnknownCommandIsNamedAndExits2) {
  const Result r = run("nosuch");
  expect_one_error_line(r, "unknown command 'nosuch'");
  // The known ones are listed (other branches add commands: only these are certain).
  for (const char* name : {"info", "render", "probes", "reference", "compare", "devices"})
    EXPECT_TRUE(contains(r.err, name)) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

TEST_F(CommandLineCli, UnknownCommandWithHelpIsStillAnError) {
  expect_one_error_line(run("nosuch --help"), "unknown command 'nosuch'");
  expect_one_error_line(run("--help nosuch"), "unknown command 'nosuch'");
}

TEST_F(CommandLineCli, KnownCommandsAndTheMainHelpStillWork) {
  const Result help = run("--help");
  EXPECT_EQ(help.code, 0) << help.err;
  EXPECT_TRUE(contains(help.out, "render")) << help.out;
  const Result version = run("--version");
  EXPECT_EQ(version.code, 0) << version.err;
  EXPECT_TRUE(contains(version.out, "ddish 0.1.0")) << version.out;
  const Result render_help = run("render --help");
  EXPECT_EQ(render_help.code, 0) << render_help.err;
  // No command at all is still CLI11's message, on one line.
  expect_one_error_line(run(""), "A subcommand is required");
}

TEST_F(CommandLineCli, BouncesHelpSaysTheFirstHitCounts) {
  for (const char* command : {"render", "probes"}) {
    const Result r = run(std::string(command) + " --help");
    EXPECT_EQ(r.code, 0) << command;
    EXPECT_TRUE(contains(r.out, "the probe ray's first hit counting as one")) << r.out;
    EXPECT_TRUE(contains(r.out, "1 direct light at the first hit")) << r.out;
  }
  const Result r = run("reference --help");
  EXPECT_EQ(r.code, 0);
  EXPECT_TRUE(contains(r.out, "the camera ray's hit counting as one")) << r.out;
  EXPECT_TRUE(contains(r.out, "1 direct light only")) << r.out;
}

TEST_F(CommandLineCli, CompareHelpSaysReferenceSecondAndClampedSrgb) {
  const Result r = run("compare --help");
  EXPECT_EQ(r.code, 0);
  EXPECT_TRUE(contains(r.out, "the reference comes second")) << r.out;
  EXPECT_TRUE(contains(r.out, "clamped to [0, 1] and sRGB-encoded")) << r.out;
}

}  // namespace
