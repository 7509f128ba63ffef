// Device enumeration, the default-device rule and --device N.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gpu/device_info.h"
#include "gpu/error.h"
#include "gpu_test.h"

namespace ddish::gpu::test {
namespace {

DeviceInfo fake(std::uint32_t index, DeviceType type, std::uint32_t api = VK_API_VERSION_1_3) {
  DeviceInfo info;
  info.index = index;
  info.name = "fake " + std::to_string(index);
  info.type = type;
  info.api_version = api;
  info.queue_family = 0;
  return info;
}

TEST(DeviceSelection, PrefersDiscreteThenIntegratedThenVirtualThenCpu) {
  using enum DeviceType;
  EXPECT_EQ(default_device_index({fake(0, cpu), fake(1, discrete)}), 1u);
  EXPECT_EQ(default_device_index({fake(0, cpu), fake(1, integrated), fake(2, discrete)}), 2u);
  EXPECT_EQ(default_device_index({fake(0, cpu), fake(1, integrated)}), 1u);
  EXPECT_EQ(default_device_index({fake(0, cpu), fake(1, virtual_gpu)}), 1u);
  EXPECT_EQ(default_device_index({fake(0, other), fake(1, cpu)}), 1u);
  EXPECT_EQ(default_device_index({fake(0, discrete), fake(1, discrete)}), 0u);
  EXPECT_EQ(default_device_index({}), std::nullopt);
}

TEST(DeviceSelection, SkipsUnusableDevices) {
  using enum DeviceType;
  DeviceInfo old_gpu = fake(0, discrete, VK_API_VERSION_1_2);
  DeviceInfo no_graphics = fake(1, integrated);
  no_graphics.queue_family.reset();
  EXPECT_FALSE(old_gpu.usable());
  EXPECT_NE(old_gpu.unusable_reason().find("1.2.0"), std::string::npos);
  EXPECT_FALSE(no_graphics.usable());
  EXPECT_EQ(default_device_index({old_gpu, no_graphics, fake(2, cpu)}), 2u);
  EXPECT_EQ(default_device_index({old_gpu, no_graphics}), std::nullopt);
  try {
    select_device({old_gpu, no_graphics}, std::nullopt);
    FAIL() << "an unusable device was selected by default";
  } catch (const GpuError& e) {
    EXPECT_STREQ(e.what(),
                 "no usable Vulkan device (0: fake 0, Vulkan 1.2.0 (ddish needs 1.3); 1: fake 1, "
                 "no queue family with both graphics and compute)");
  }

  try {
    select_device({old_gpu}, 0u);
    FAIL() << "an unusable device was selected";
  } catch (const GpuError& e) {
    EXPECT_STREQ(e.what(),
                 "Vulkan device 0 (fake 0) cannot be used: Vulkan 1.2.0 (ddish needs 1.3)");
  }
}

TEST(DeviceSelection, ExplicitIndexOverridesAndOutOfRangeThrows) {
  using enum DeviceType;
  const std::vector<DeviceInfo> devices = {fake(0, cpu), fake(1, discrete)};
  EXPECT_EQ(select_device(devices, std::nullopt), 1u);
  EXPECT_EQ(select_device(devices, 0u), 0u);
  try {
    select_device(devices, 99u);
    FAIL() << "device 99 was selected";
  } catch (const GpuError& e) {
    EXPECT_STREQ(e.what(),
                 "Vulkan device 99 does not exist: 2 devices found (0: fake 0, 1: fake 1)");
  }
  try {
    select_device({}, std::nullopt);
    FAIL() << "a device was selected from none";
  } catch (const GpuError& e) {
    EXPECT_NE(std::string(e.what()).find("no Vulkan device found"), std::string::npos);
  }
}

TEST(DeviceSelection, Formatting) {
  EXPECT_EQ(version_string(VK_MAKE_API_VERSION(0, 1, 3, 230)), "1.3.230");
  EXPECT_EQ(sample_counts(VK_SAMPLE_COUNT_1_BIT | VK_SAMPLE_COUNT_4_BIT),
            (std::vector<std::uint32_t>{1, 4}));
  EXPECT_EQ(sample_counts(0), std::vector<std::uint32_t>{});
  DeviceInfo nvidia = fake(0, DeviceType::discrete);
  nvidia.vendor_id = 0x10DE;
  nvidia.driver_version = (535u << 22) | (104u << 14) | (5u << 6);
  EXPECT_EQ(driver_version_string(nvidia), "535.104.5.0");
  EXPECT_EQ(type_name(DeviceType::cpu), "CPU");
  EXPECT_EQ(type_name(DeviceType::discrete), "discrete GPU");
}

class Devices : public GpuTest {};

TEST_F(Devices, EnumeratesTheDevicesOfTheMachine) {
  const std::vector<DeviceInfo> devices = enumerate_devices(gpu().instance());
  ASSERT_FALSE(devices.empty());
  const auto chosen = default_device_index(devices);
  ASSERT_TRUE(chosen.has_value());
  EXPECT_EQ(*chosen, device().info().index);
  for (std::uint32_t i = 0; i < devices.size(); ++i) {
    const DeviceInfo& d = devices[i];
    EXPECT_EQ(d.index, i);
    EXPECT_FALSE(d.name.empty());
    EXPECT_GE(d.api_version, VK_API_VERSION_1_0);
    if (!d.usable()) continue;
    // Vulkan guarantees single-sampled attachments and, where multiview exists, at least 6 views.
    EXPECT_NE(d.color_sample_counts & VK_SAMPLE_COUNT_1_BIT, 0u);
    EXPECT_NE(d.msaa_sample_counts() & VK_SAMPLE_COUNT_1_BIT, 0u);
    EXPECT_GE(d.max_multiview_view_count, 6u);
    EXPECT_GT(d.timestamp_period, 0.0f);
    EXPECT_GT(d.limits.maxComputeWorkGroupInvocations, 0u);
  }
}

TEST_F(Devices, OpensAGraphicsAndComputeQueue) {
  const DeviceInfo& info = device().info();
  EXPECT_TRUE(info.usable());
  ASSERT_TRUE(info.queue_family.has_value());
  EXPECT_EQ(device().queue_family(), *info.queue_family);
  EXPECT_NE(device().queue(), VK_NULL_HANDLE);
  EXPECT_GE(info.api_version, VK_API_VERSION_1_3);
  // Multiview is core since 1.1 and required by 1.3 drivers; the renderer depends on it.
  EXPECT_TRUE(device().features().multiview);
  EXPECT_TRUE(device().features().maintenance4);  // mandatory in 1.3; shaders rely on it
  EXPECT_GT(device().memory_properties().memoryTypeCount, 0u);
  EXPECT_NO_THROW(device().wait_idle());
}

TEST_F(Devices, AnExplicitIndexOpensThatDevice) {
  const std::uint32_t index = device().info().index;
  Device again(gpu().instance(), {.index = index});
  EXPECT_EQ(again.info().index, index);
  EXPECT_EQ(again.info().name, device().info().name);
}

TEST(DeviceIndex, NinetyNineIsOutOfRange) {
  try {
    Context context({.validation = true, .device_index = 99u});
    FAIL() << "device 99 was opened";
  } catch (const GpuError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("Vulkan device 99 does not exist: ", 0), 0u) << message;
    EXPECT_NE(message.find("found (0: "), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
  }
}

TEST(DeviceIndex, NoDriverAtAllIsOneClearLine) {
  // The loader reads its driver list from these variables at each vkCreateInstance; pointing
  // both spellings at nothing is a machine without Vulkan drivers.
  ScopedEnv old_name("VK_ICD_FILENAMES", "/nonexistent/ddish_no_driver.json");
  ScopedEnv new_name("VK_DRIVER_FILES", "/nonexistent/ddish_no_driver.json");
  try {
    Context context;
    FAIL() << "a Vulkan device was opened without a driver";
  } catch (const GpuError& e) {
    EXPECT_STREQ(e.what(),
                 "no Vulkan driver found (install mesa-vulkan-drivers for the CPU device)");
  }
}


TEST(DeviceCreation, CallersCanCreateTheHandlesFromTheCreateInfosBuiltHere) {
  // What OpenXR's binding does (xrCreateVulkanInstanceKHR / xrCreateVulkanDeviceKHR): the
  // caller creates the handles itself from gpu/'s create infos; gpu/ still destroys them.
  int instances = 0, devices = 0, picks = 0;
  std::uint32_t layers_seen = 0;
  VkPhysicalDevice picked = VK_NULL_HANDLE;
  ContextOptions options = validated_options();
  options.create_instance = [&](const VkInstanceCreateInfo& info, VkInstance* out) {
    ++instances;
    layers_seen = info.enabledLayerCount;
    return vkCreateInstance(&info, nullptr, out);
  };
  options.pick_physical = [&](VkInstance instance) {
    ++picks;
    std::uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance, &count, nullptr);
    std::vector<VkPhysicalDevice> all(count);
    vkEnumeratePhysicalDevices(instance, &count, all.data());
    picked = all.back();  // not necessarily the default: the caller's choice must hold
    return picked;
  };
  options.create_device = [&](VkPhysicalDevice physical, const VkDeviceCreateInfo& info,
                              VkDevice* out) {
    ++devices;
    EXPECT_EQ(physical, picked);
    return vkCreateDevice(physical, &info, nullptr, out);
  };
  std::shared_ptr<const ValidationLog> log;
  {
    Context context(options);
    log = context.instance().shared_validation();
    EXPECT_EQ(context.device().physical(), picked);
    EXPECT_TRUE(context.instance().validation_enabled());
    EXPECT_NO_THROW(context.device().wait_idle());
  }
  EXPECT_EQ(instances, 1);
  EXPECT_EQ(picks, 1);
  EXPECT_EQ(devices, 1);
  EXPECT_EQ(layers_seen, 1u);  // the validation layer went into the caller's create info
  EXPECT_EQ(log->errors(), 0u) << describe_errors(*log);  // destroyed here, nothing leaked
}

TEST(DeviceCreation, AMissingExtensionIsNamed) {
  try {
    Context context({.device_extensions = {"VK_DDISH_no_such_extension"}});
    FAIL() << "a device was made with an extension nobody has";
  } catch (const GpuError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(" has no VK_DDISH_no_such_extension extension"), std::string::npos)
        << message;
  }
  try {
    Context context({.instance_extensions = {"VK_DDISH_no_such_instance_extension"}});
    FAIL() << "an instance was made with an extension nobody has";
  } catch (const GpuError& e) {
    EXPECT_STREQ(e.what(), "the Vulkan instance has no VK_DDISH_no_such_instance_extension extension");
  }
}

TEST(DeviceCreation, ListedExtensionsAreEnabled) {
  // A window's pair: VK_KHR_surface on the instance, VK_KHR_swapchain on the device (which needs
  // the former: validation says so). Neither needs a display server until a surface is made.
  ContextOptions options = validated_options();
  options.instance_extensions = {VK_KHR_SURFACE_EXTENSION_NAME};
  options.device_extensions = {VK_KHR_SWAPCHAIN_EXTENSION_NAME};
  std::shared_ptr<const ValidationLog> log;
  {
    Context with(options);
    log = with.instance().shared_validation();
    EXPECT_NE(vkGetDeviceProcAddr(with.device().handle(), "vkCreateSwapchainKHR"), nullptr);
    Context without(validated_options());
    EXPECT_EQ(vkGetDeviceProcAddr(without.device().handle(), "vkCreateSwapchainKHR"), nullptr);
  }
  EXPECT_EQ(log->errors(), 0u) << describe_errors(*log);
}

}  // namespace
}  // namespace ddish::gpu::test

namespace ddish::gpu::test {
namespace {

// Out of memory and a lost device say what they mean to a user, in one line.
TEST(GpuErrors, ResourceFailuresNameTheRemedy) {
  const auto message = [](VkResult r) {
    try {
      check(r, "vkAllocateMemory of 64 bytes");
    } catch (const GpuError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message(VK_SUCCESS), "");
  const std::string oom = message(VK_ERROR_OUT_OF_DEVICE_MEMORY);
  EXPECT_NE(oom.find("VK_ERROR_OUT_OF_DEVICE_MEMORY (out of memory:"), std::string::npos) << oom;
  const std::string lost = message(VK_ERROR_DEVICE_LOST);
  EXPECT_NE(lost.find("the GPU was reset"), std::string::npos) << lost;
  for (const std::string& m : {oom, lost, message(VK_ERROR_INITIALIZATION_FAILED)})
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
}

}  // namespace
}  // namespace ddish::gpu::test
