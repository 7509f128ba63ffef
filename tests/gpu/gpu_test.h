// The fixture every GPU test uses: a fresh Context with the Khronos validation layer (and its
// synchronization checks) for each test, destroyed at the end of the test, which then fails if
// the layer reported any error, including leaks found when the device and instance go away.
// Without the layer the test fails at once and says how to install it.
#pragma once

#include <cstdlib>
#include <memory>
#include <optional>
#include <string>

#include <gtest/gtest.h>

#include "gpu/context.h"
#include "gpu/error.h"

namespace ddish::gpu::test {

inline ContextOptions validated_options() {
  return {.validation = true, .synchronization_validation = true, .application_name = "test_gpu"};
}

// Appends the validation errors of `log` to a failure message.
inline std::string describe_errors(const ValidationLog& log) {
  std::string text = std::to_string(log.errors()) + " Vulkan validation error(s):";
  for (const auto& message : log.error_messages()) text += "\n  " + message;
  return text;
}

// Sets an environment variable for one scope and restores what was there.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (old_)
      setenv(name_, old_->c_str(), 1);
    else
      unsetenv(name_);
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

class GpuTest : public ::testing::Test {
 protected:
  void SetUp() override {
    try {
      context_ = std::make_unique<Context>(validated_options());
    } catch (const GpuError& e) {
      FAIL() << "cannot start a validated Vulkan context: " << e.what();
    }
    log_ = context_->instance().shared_validation();
  }

  void TearDown() override {
    context_.reset();  // device and instance destruction report leaks into the log
    if (log_ && log_->errors() != 0) ADD_FAILURE() << describe_errors(*log_);
  }

  Context& gpu() { return *context_; }
  Device& device() { return context_->device(); }

 private:
  std::unique_ptr<Context> context_;
  std::shared_ptr<const ValidationLog> log_;
};

}  // namespace ddish::gpu::test
