// SPIR-V shaders. The build compiles shaders/NAME (GLSL) to NAME.spv in the build tree, whose
// path is compiled in as DDISH_SHADER_DIR; the environment variable of the same name points
// an installed or relocated binary elsewhere.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string_view>
#include <vector>

#include <vulkan/vulkan.h>

#include "gpu/handle.h"

namespace ddish::gpu {

class Device;

// $DDISH_SHADER_DIR when set and not empty, else the build tree's shader directory.
std::filesystem::path shader_dir();

// Where the SPIR-V of a shader source file lives: shader_path("fill_pattern.comp") is
// shader_dir() / "fill_pattern.comp.spv".
std::filesystem::path shader_path(std::string_view source_name);

// The words of a SPIR-V file. Throws GpuError naming the path when the file is missing,
// unreadable, or not SPIR-V (wrong magic number, size not a multiple of four bytes).
std::vector<std::uint32_t> load_spirv(const std::filesystem::path& path);

class ShaderModule {
 public:
  ShaderModule(const Device& device, std::span<const std::uint32_t> code);
  // Loads shader_path(source_name) and creates the module.
  static ShaderModule load(const Device& device, std::string_view source_name);

  VkShaderModule handle() const { return module_.get(); }

 private:
  DeviceHandle<VkShaderModule, vkDestroyShaderModule> module_;
};

}  // namespace ddish::gpu
