// The validation plumbing itself: the layer is there, the fixture's context runs with it, and a
// deliberate misuse is caught and counted, so that a clean run means something.
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "gpu/instance.h"
#include "gpu_test.h"

namespace ddish::gpu::test {
namespace {

TEST(Validation, LayerIsInstalled) {
  EXPECT_TRUE(validation_layer_available())
      << kValidationLayer << " is missing: install vulkan-validationlayers (scripts/bootstrap.sh)";
}

class ValidatedContext : public GpuTest {};

TEST_F(ValidatedContext, RunsWithTheLayerAndNoErrors) {
  EXPECT_TRUE(gpu().instance().validation_enabled());
  EXPECT_EQ(gpu().validation().errors(), 0u);
}

TEST(Validation, AMisuseIsCountedAndNamed) {
  Context context(validated_options());
  ValidationLog& log = context.instance().validation();
  log.set_echo(false);  // the error below is expected; keep the test output clean
  ASSERT_EQ(log.errors(), 0u);

  // A buffer with no usage flags is invalid (VUID-VkBufferCreateInfo-usage-requiredbitmask) yet
  // harmless for the driver, which creates it anyway.
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = 64;
  info.usage = 0;
  VkBuffer buffer = VK_NULL_HANDLE;
  const VkResult result = vkCreateBuffer(context.device().handle(), &info, nullptr, &buffer);
  if (result == VK_SUCCESS) vkDestroyBuffer(context.device().handle(), buffer, nullptr);

  EXPECT_GE(log.errors(), 1u);
  const auto messages = log.error_messages();
  ASSERT_FALSE(messages.empty());
  EXPECT_NE(messages.front().find("VUID-VkBufferCreateInfo-usage"), std::string::npos)
      << messages.front();
}

TEST(Validation, LeaksAreReportedWhenTheDeviceGoesAway) {
  auto context = std::make_unique<Context>(validated_options());
  context->instance().validation().set_echo(false);
  const std::shared_ptr<const ValidationLog> log = context->instance().shared_validation();
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = 64;
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  VkBuffer leaked = VK_NULL_HANDLE;
  ASSERT_EQ(vkCreateBuffer(context->device().handle(), &info, nullptr, &leaked), VK_SUCCESS);
  EXPECT_EQ(log->errors(), 0u);
  context.reset();  // vkDestroyDevice with a live buffer: the layer reports it
  EXPECT_GE(log->errors(), 1u);
}

TEST(Validation, OffMeansNoLayerAndNoCounts) {
  if (validation_requested_by_environment()) GTEST_SKIP() << "DDISH_VALIDATION is set";
  Instance instance({.validation = false});
  EXPECT_FALSE(instance.validation_enabled());
  EXPECT_EQ(instance.validation().errors(), 0u);
}

}  // namespace
}  // namespace ddish::gpu::test
