// The material sampler's anisotropic filtering (RendererOptions::anisotropy), resolved against
// the device. Automatic (0) is 8x on GPUs and off on CPU devices: lavapipe's anisotropic filter
// (Mesa 22.3 llvmpipe) can take unbounded time where texture derivatives are extreme (grazing
// floors, surfaces right at the near plane). Measured with bench/raster_views on the 48-view
// Sponza rig at 210x280, MSAA 1, one pass per view, on the loaded 2-core box: with 8x, view 38
// alone took 63,180 ms of forward GPU time (view 14 2,274 ms, view 30 1,497 ms) and the median
// view 373 ms; with it off view 38 took 138 ms, the slowest view 185 ms, the median 131 ms, the
// 48 views 6.3 s instead of 83.7 s. (A public report of the same: pal1000/mesa-dist-win#86,
// an llvmpipe freeze from Mesa 21.3 on, traced there to its anisotropic filtering.) The probe
// tracer filters textures isotropically (ray cones) anyway.
#pragma once

#include "gpu/device_info.h"

namespace ddish::raster {

inline constexpr int kAutomaticAnisotropy = 0;  // 8x on GPUs, off on CPU devices
inline constexpr int kMaxAnisotropyOption = 16; // Vulkan's minimum maxSamplerAnisotropy

// Throws std::invalid_argument unless 0 <= requested <= 16 (0: automatic, 1: off).
void check_anisotropy(int requested);

// The sampler's maxAnisotropy: 1 means anisotropic filtering off. Automatic is 8 where `type`
// is not a CPU device, else 1; an explicit value is clamped to `device_limit`
// (maxSamplerAnisotropy), and a device without the samplerAnisotropy feature gets 1 whatever
// is asked. Throws std::invalid_argument as check_anisotropy does.
float resolve_anisotropy(int requested, gpu::DeviceType type, bool feature, float device_limit);

}  // namespace ddish::raster
