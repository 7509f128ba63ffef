// io/child_process: work run in a forked child with a deadline. Each way a child can end is one
// outcome, and the answer crosses the pipe whole, however large.
#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>
#include <string>

#include "io/child_process.h"

using ddish::io::ChildOutcome;
using ddish::io::run_in_child;
using namespace std::chrono_literals;

TEST(ChildProcess, TheAnswerComesBackWholeAndSeesTheParentsMemory) {
  // 5 MiB: many times the pipe's buffer, so the parent must read while the child writes.
  std::string pattern(5 << 20, '\0');
  for (std::size_t i = 0; i < pattern.size(); ++i) pattern[i] = static_cast<char>(i * 131 % 251);
  const ChildOutcome out = run_in_child([&] { return pattern; }, 20s);
  ASSERT_EQ(out.status, ChildOutcome::Status::kOk) << out.bytes;
  EXPECT_TRUE(out.bytes == pattern);
}

TEST(ChildProcess, AnExceptionIsItsMessage) {
  const ChildOutcome out = run_in_child([]() -> std::string { throw std::runtime_error("bad stream"); }, 20s);
  EXPECT_EQ(out.status, ChildOutcome::Status::kFailed);
  EXPECT_EQ(out.bytes, "bad stream");
}

TEST(ChildProcess, AnEmptyAnswerIsAnAnswer) {
  const ChildOutcome out = run_in_child([] { return std::string(); }, 20s);
  EXPECT_EQ(out.status, ChildOutcome::Status::kOk);
  EXPECT_TRUE(out.bytes.empty());
}

TEST(ChildProcess, WorkThatDoesNotEndIsKilledAtTheDeadline) {
  const ChildOutcome out = run_in_child(
      []() -> std::string {
        volatile unsigned spin = 0;
        for (;;) spin = spin + 1;
      },
      300ms);
  EXPECT_EQ(out.status, ChildOutcome::Status::kTimedOut);
  EXPECT_TRUE(out.bytes.empty());
}

TEST(ChildProcess, ACrashIsNamedBySignal) {
  const ChildOutcome out = run_in_child([]() -> std::string { std::abort(); }, 20s);
  EXPECT_EQ(out.status, ChildOutcome::Status::kCrashed);
  EXPECT_NE(out.bytes.find("killed by signal 6"), std::string::npos) << out.bytes;
}

TEST(ChildProcess, AnExitWithoutAnAnswerIsACrash) {
  const ChildOutcome out = run_in_child([]() -> std::string { std::_Exit(3); }, 20s);
  EXPECT_EQ(out.status, ChildOutcome::Status::kCrashed);
  EXPECT_EQ(out.bytes, "exited with status 3 without an answer");
}
