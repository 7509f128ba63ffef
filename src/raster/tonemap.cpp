#include "raster/tonemap.h"

#include <stdexcept>

#include "gpu/buffer.h"
#include "gpu/shader.h"

namespace ddish::raster {

namespace {

struct TonemapParams {
  std::uint32_t pixels;
  std::uint32_t curve;
  float exposure;
};

}  // namespace

ToneCurve parse_tone_curve(const std::string& name) {
  if (name == "linear") return ToneCurve::linear;
  if (name == "filmic") return ToneCurve::filmic;
  throw std::invalid_argument("--tonemap must be linear or filmic, got '" + name + "'");
}

const char* tone_curve_name(ToneCurve curve) {
  return curve == ToneCurve::filmic ? "filmic" : "linear";
}

Tonemapper::Tonemapper(const gpu::Device& device)
    : pipeline_(device, gpu::ShaderModule::load(device, "tonemap.comp"),
                {.storage_buffers = 2, .push_constant_bytes = sizeof(TonemapParams)}) {}

void Tonemapper::record(VkCommandBuffer cmd, const gpu::Buffer& hdr, const gpu::Buffer& display,
                        std::uint32_t pixels, ToneCurve curve, float exposure) {
  // Rebinding is only allowed between submissions; the renderer keeps the same buffers.
  if (bound_hdr_ != hdr.handle() || bound_display_ != display.handle()) {
    pipeline_.bind_buffers({&hdr, &display});
    bound_hdr_ = hdr.handle();
    bound_display_ = display.handle();
  }
  pipeline_.bind(cmd);
  pipeline_.push(cmd, TonemapParams{pixels, static_cast<std::uint32_t>(curve), exposure});
  pipeline_.dispatch(cmd, gpu::group_count(pixels, 64));
}

}  // namespace ddish::raster
