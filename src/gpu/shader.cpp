#include "gpu/shader.h"

#include <cstdlib>
#include <fstream>
#include <string>

#include "gpu/device.h"
#include "gpu/error.h"

namespace ddish::gpu {

namespace {
constexpr std::uint32_t kSpirvMagic = 0x07230203;
}

std::filesystem::path shader_dir() {
  if (const char* dir = std::getenv("DDISH_SHADER_DIR"); dir != nullptr && dir[0] != '\0')
    return dir;
  return DDISH_SHADER_DIR;
}

std::filesystem::path shader_path(std::string_view source_name) {
  return shader_dir() / (std::string(source_name) + ".spv");
}

std::vector<std::uint32_t> load_spirv(const std::filesystem::path& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error))
    throw GpuError("SPIR-V file not found: " + path.string() +
                   " (build the ddish_shaders target, or point DDISH_SHADER_DIR at the .spv files)");
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw GpuError("cannot open SPIR-V file " + path.string());
  const std::streamsize bytes = in.tellg();
  if (bytes <= 0 || bytes % 4 != 0)
    throw GpuError("not a SPIR-V file (size " + std::to_string(bytes) +
                   " bytes is not a positive multiple of 4): " + path.string());
  std::vector<std::uint32_t> words(static_cast<std::size_t>(bytes) / 4);
  in.seekg(0);
  if (!in.read(reinterpret_cast<char*>(words.data()), bytes))
    throw GpuError("cannot read SPIR-V file " + path.string());
  if (words[0] != kSpirvMagic)
    throw GpuError("not a SPIR-V file (bad magic number): " + path.string());
  return words;
}

ShaderModule::ShaderModule(const Device& device, std::span<const std::uint32_t> code) {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = code.size_bytes();
  info.pCode = code.data();
  VkShaderModule module = VK_NULL_HANDLE;
  check(vkCreateShaderModule(device.handle(), &info, nullptr, &module), "vkCreateShaderModule");
  module_ = DeviceHandle<VkShaderModule, vkDestroyShaderModule>(device.handle(), module);
}

ShaderModule ShaderModule::load(const Device& device, std::string_view source_name) {
  const std::vector<std::uint32_t> code = load_spirv(shader_path(source_name));
  return ShaderModule(device, code);
}

}  // namespace ddish::gpu
