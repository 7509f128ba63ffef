// A Looking Glass lenticular calibration: the per-device numbers (the "visual.json" a device
// carries, also what HoloPlay Service / Looking Glass Bridge report) that say how the panel's
// subpixels map onto the lenticular sheet's views. Fields are read as Looking Glass writes them,
// each either {"value": x} or a bare number:
//   pitch (lenticules per inch), slope (panel pixels per lenticule step, signed), center (phase of
//   the sheet at the panel's bottom-left, in views), DPI, screenW, screenH (panel pixels),
//   invView (1: views run right to left), flipImageX, flipImageY (panel mounted mirrored),
//   flipSubp (BGR subpixel order), viewCone (degrees, optional).
// Other keys (serial, configVersion, verticalAngle, subpixel cell tables...) are ignored.
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

namespace ddish::display {

class CalibrationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Calibration {
  double pitch = 0.0;
  double slope = 0.0;
  double center = 0.0;
  double dpi = 0.0;
  int screen_width = 0;
  int screen_height = 0;
  bool inv_view = false;
  bool flip_x = false;
  bool flip_y = false;
  bool flip_subpixels = false;
  std::optional<double> view_cone_deg;
};

// Throws CalibrationError ("SOURCE: field 'slope' is missing") on bad JSON or fields: pitch, DPI,
// screenW, screenH must be positive, slope non-zero.
Calibration parse_calibration(const std::string& json_text, const std::string& source);
Calibration load_calibration(const std::filesystem::path& path);

}  // namespace ddish::display
