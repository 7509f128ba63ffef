#include "display/calibration.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

namespace ddish::display {

namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::string& source, const std::string& key,
                       const std::string& problem) {
  throw CalibrationError(source + ": field '" + key + "' " + problem);
}

// Looking Glass files wrap every number as {"value": x}; accept bare numbers too.
std::optional<double> read_number(const json& doc, const std::string& key,
                                  const std::string& source) {
  if (!doc.contains(key)) return std::nullopt;
  const json* v = &doc.at(key);
  if (v->is_object()) {
    if (!v->contains("value")) fail(source, key, "has no 'value'");
    v = &v->at("value");
  }
  if (v->is_boolean()) return v->get<bool>() ? 1.0 : 0.0;
  if (!v->is_number()) fail(source, key, "must be a number");
  const double d = v->get<double>();
  if (!std::isfinite(d)) fail(source, key, "must be finite");
  return d;
}

double required(const json& doc, const std::string& key, const std::string& source) {
  const auto v = read_number(doc, key, source);
  if (!v) fail(source, key, "is missing");
  return *v;
}

double positive(const json& doc, const std::string& key, const std::string& source) {
  const double d = required(doc, key, source);
  if (!(d > 0.0)) fail(source, key, "must be positive");
  return d;
}

int pixels(const json& doc, const std::string& key, const std::string& source) {
  const double d = positive(doc, key, source);
  if (d != std::floor(d) || d > 1e6) fail(source, key, "must be a whole number of pixels");
  return static_cast<int>(d);
}

bool flag(const json& doc, const std::string& key, const std::string& source) {
  return read_number(doc, key, source).value_or(0.0) >= 0.5;
}

}  // namespace

Calibration parse_calibration(const std::string& json_text, const std::string& source) {
  json doc;
  try {
    doc = json::parse(json_text);
  } catch (const json::parse_error& e) {
    throw CalibrationError(source + ": not valid JSON: " + e.what());
  }
  if (!doc.is_object()) throw CalibrationError(source + ": a calibration must be an object");
  Calibration c;
  c.pitch = positive(doc, "pitch", source);
  c.slope = required(doc, "slope", source);
  if (c.slope == 0.0) fail(source, "slope", "must not be zero");
  c.center = required(doc, "center", source);
  c.dpi = positive(doc, "DPI", source);
  c.screen_width = pixels(doc, "screenW", source);
  c.screen_height = pixels(doc, "screenH", source);
  c.inv_view = flag(doc, "invView", source);
  c.flip_x = flag(doc, "flipImageX", source);
  c.flip_y = flag(doc, "flipImageY", source);
  c.flip_subpixels = flag(doc, "flipSubp", source);
  c.view_cone_deg = read_number(doc, "viewCone", source);
  return c;
}

Calibration load_calibration(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw CalibrationError(path.string() + ": cannot open calibration");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_calibration(text.str(), path.string());
}

}  // namespace ddish::display
