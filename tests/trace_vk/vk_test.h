// The GPU probe tracer's tests run on a device with Vulkan ray tracing (Mesa 25 lavapipe here
// and in CI) under the Khronos validation layer with its synchronization checks, as every GPU
// test does (tests/gpu/gpu_test.h); on a device without ray tracing (Mesa 22) they skip,
// saying why.
#pragma once

#include <memory>

#include <gtest/gtest.h>

#include "../gpu/gpu_test.h"
#include "gpu/context.h"

namespace ddish::trace_vk::test {

class VkTracerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    gpu::ContextOptions options = gpu::test::validated_options();
    options.ray_tracing = true;
    try {
      context_ = std::make_unique<gpu::Context>(options);
    } catch (const gpu::GpuError& e) {
      FAIL() << "cannot start a validated Vulkan context: " << e.what();
    }
    log_ = context_->instance().shared_validation();
    if (!context_->device().features().ray_tracing)
      GTEST_SKIP() << context_->device().info().name << " (" << context_->device().info().driver_info
                   << ") has no Vulkan ray-tracing pipelines";
  }

  void TearDown() override {
    context_.reset();
    if (log_ && log_->errors() != 0) ADD_FAILURE() << gpu::test::describe_errors(*log_);
  }

  gpu::Device& device() { return context_->device(); }

 private:
  std::unique_ptr<gpu::Context> context_;
  std::shared_ptr<const gpu::ValidationLog> log_;
};

}  // namespace ddish::trace_vk::test
