#include "app/raster_options.h"

#include <stdexcept>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "raster/shading_pass.h"

namespace ddish::app {

void add_raster_options(CLI::App& cmd, RasterArgs& a) {
  cmd.add_option("--msaa", a.msaa, "samples per pixel (default: 4 where supported, else 1)");
  cmd.add_flag("--sample-shading", a.sample_shading, "shade every MSAA sample");
  cmd.add_option("--depth-prepass", a.depth_prepass,
                  "draw depth first, then light only the nearest surface of each pixel: auto is on "
                  "where the device has VK_EXT_post_depth_coverage (lavapipe has it); the same image")
      ->check(CLI::IsMember({"auto", "on", "off"}))
      ->capture_default_str();
  cmd.add_option("--shading-pass", a.shading_pass,
                  "forward: shade triangles as they are drawn; visibility: draw instance and triangle ids "
                  "first, then shade each pixel once (the same image, cheaper on CPU devices); auto is "
                  "visibility where the device has non-uniform texture indexing (Mesa 25 lavapipe) and "
                  "neither --sample-shading nor --depth-prepass on|off is given, else forward")
      ->check(CLI::IsMember({"auto", "forward", "visibility"}))
      ->capture_default_str();
  cmd.add_option("--max-gpu-memory", a.max_gpu_memory_mb,
                  "MiB the frame's render target and readback may take (batches shrink to fit; a view "
                  "that cannot fit is an error before the run); 0: what the device has free")
      ->capture_default_str();
  cmd.add_option("--view-batch", a.view_batch,
                  "views drawn per submission into one reused target; 0: the most whose target "
                  "fits 256 MiB (fewer means less memory, more submissions)")
      ->capture_default_str();
  cmd.add_option("--anisotropy", a.anisotropy,
                  "texture anisotropic filtering: maximum 2..16 (clamped to the device), 1 off, "
                  "0 automatic: 8 on GPUs, off on CPU devices (lavapipe, where it can stall a view)")
      ->capture_default_str();
}

void check_raster_options(const RasterArgs& a) {
  if (a.msaa != 0 && a.msaa != 1 && a.msaa != 2 && a.msaa != 4 && a.msaa != 8 && a.msaa != 16)
    throw std::invalid_argument(fmt::format("--msaa must be 1, 2, 4, 8 or 16, got {}", a.msaa));
  try {
    raster::check_anisotropy(a.anisotropy);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("--") + e.what());
  }
}

raster::RendererOptions renderer_options(const RasterArgs& a) {
  raster::RendererOptions ro;
  ro.msaa = a.msaa;
  ro.sample_shading = a.sample_shading;
  if (a.depth_prepass != "auto") ro.depth_prepass = a.depth_prepass == "on";
  if (a.shading_pass != "auto") ro.shading_pass = raster::parse_shading_pass(a.shading_pass);
  ro.anisotropy = a.anisotropy;
  ro.batch_views = a.view_batch;
  ro.memory_limit_bytes = std::uint64_t{a.max_gpu_memory_mb} << 20;
  return ro;
}

}  // namespace ddish::app
