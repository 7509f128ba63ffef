// `ddish devices`: the Vulkan devices this machine offers, what the renderer cares about in each
// (multiview views, MSAA, timestamps), and which one `ddish render` opens without --device.
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include "app/commands.h"
#include "gpu/device_info.h"
#include "gpu/error.h"
#include "gpu/instance.h"

namespace ddish::app {
namespace {

std::string join_counts(VkSampleCountFlags flags) {
  std::string text;
  for (std::uint32_t count : gpu::sample_counts(flags)) {
    if (!text.empty()) text += ' ';
    text += std::to_string(count);
  }
  return text.empty() ? "none" : text;
}

void print_device(const gpu::DeviceInfo& d, bool is_default) {
  fmt::print("device {}: {}{}\n", d.index, d.name, is_default ? "  [default]" : "");
  fmt::print("  type                   {}\n", gpu::type_name(d.type));
  fmt::print("  API version            {}\n", gpu::version_string(d.api_version));
  std::string driver = gpu::driver_version_string(d);
  if (!d.driver_name.empty()) driver += " (" + d.driver_name + ": " + d.driver_info + ")";
  fmt::print("  driver version         {}\n", driver);
  fmt::print("  maxMultiviewViewCount  {}\n", d.max_multiview_view_count);
  fmt::print("  MSAA sample counts     {} (colour {}, depth {})\n",
             join_counts(d.msaa_sample_counts()), join_counts(d.color_sample_counts),
             join_counts(d.depth_sample_counts));
  if (d.queue_family)
    fmt::print("  queue family           {} (graphics + compute)\n", *d.queue_family);
  if (d.timestamps_supported())
    fmt::print("  timestamps             {} bits, {} ns per tick\n", d.timestamp_valid_bits,
               d.timestamp_period);
  else
    fmt::print("  timestamps             not supported\n");
  fmt::print("  ray tracing            {}\n", d.ray_tracing ? "pipelines and acceleration structures (--tracer vulkan)" : "none");
  if (!d.usable()) fmt::print("  not usable             {}\n", d.unusable_reason());
}

Action make_devices_command(CLI::App& root) {
  CLI::App* cmd = root.add_subcommand("devices", "Vulkan devices found, and which one is the default");
  auto validation = std::make_shared<bool>(false);
  cmd->add_flag("--validation", *validation,
                "Enable VK_LAYER_KHRONOS_validation (also DDISH_VALIDATION=1)");
  return [validation]() {
    gpu::Instance instance({.validation = *validation});
    const std::vector<gpu::DeviceInfo> devices = gpu::enumerate_devices(instance);
    if (devices.empty())
      throw gpu::GpuError("no Vulkan device found (install mesa-vulkan-drivers for the CPU device)");
    const auto default_index = gpu::default_device_index(devices);
    fmt::print("Vulkan loader {}, {} device{}; default: {}\n",
               gpu::version_string(instance.loader_version()), devices.size(),
               devices.size() == 1 ? "" : "s",
               default_index ? std::to_string(*default_index) : "none usable");
    for (const auto& device : devices) {
      fmt::print("\n");
      print_device(device, default_index && *default_index == device.index);
    }
    return 0;
  };
}

}  // namespace

DDISH_COMMAND(90, make_devices_command);

}  // namespace ddish::app
