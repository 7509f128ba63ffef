// How `render` and `view` rasterize their views (raster::RendererOptions): --msaa,
// --sample-shading, --depth-prepass, --shading-pass, --max-gpu-memory, --view-batch and
// --anisotropy, registered, checked and turned into the renderer's options in one place.
#pragma once

#include <cstdint>
#include <string>

#include "raster/anisotropy.h"
#include "raster/renderer.h"

namespace CLI {
class App;
}

namespace ddish::app {

struct RasterArgs {
  std::uint32_t msaa = 0;  // 0: the renderer's default (4 where supported)
  bool sample_shading = false;
  std::string depth_prepass = "auto";  // raster::RendererOptions::depth_prepass
  std::string shading_pass = "auto";   // raster::RendererOptions::shading_pass
  int anisotropy = raster::kAutomaticAnisotropy;
  std::uint32_t view_batch = 0;         // raster::RendererOptions::batch_views
  std::uint32_t max_gpu_memory_mb = 0;  // raster::RendererOptions::memory_limit_bytes, in MiB
};

void add_raster_options(CLI::App& cmd, RasterArgs& a);
// Throws std::invalid_argument (one line naming the option) for an MSAA count or anisotropy
// the renderer cannot take.
void check_raster_options(const RasterArgs& a);
// The renderer's options these arguments ask for; the rest keep RendererOptions' defaults.
raster::RendererOptions renderer_options(const RasterArgs& a);

}  // namespace ddish::app
