#include "metrics/errors.h"

#include <cmath>
#include <cstdio>

#include "metrics/linear_error.h"
#include "metrics/psnr.h"
#include "metrics/ssim.h"

namespace ddish::metrics {

ImageErrors compute_errors(const Image& image, const Image& reference) {
  ImageErrors e;
  e.psnr = psnr(image, reference);
  e.ssim = ssim(image, reference);
  e.rmse = rmse(image, reference);
  e.relmse = relative_mse(image, reference);
  return e;
}

std::string format_figure(double value, int digits) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, value);
  return buf;
}

namespace {
nlohmann::ordered_json figure_json(double value) {
  if (std::isfinite(value)) return value;
  return format_figure(value);
}
}  // namespace

nlohmann::ordered_json to_json(const ImageErrors& errors) {
  nlohmann::ordered_json j;
  j["psnr"] = figure_json(errors.psnr);
  j["ssim"] = figure_json(errors.ssim);
  j["rmse"] = figure_json(errors.rmse);
  j["relmse"] = figure_json(errors.relmse);
  return j;
}

}  // namespace ddish::metrics
