// Display profiles (displays/*.json): how many views a display wants, their size and atlas
// layout, the aspect the projections are built for, the camera model that places the views, and
// an optional per-frame time budget. Every field is documented in docs/displays.md.
//
// Profiles are found by name in the displays folder: $DDISH_DISPLAYS_DIR when set, else the
// source tree's displays/ (compiled in), or read from a path. A bad file or field is reported as
// one line naming the file and the field (ProfileError); unknown fields are errors too, so a
// misspelt key never silently falls back to a default.
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "display/camera_grid.h"
#include "display/lightfield_rig.h"
#include "display/quilt_layout.h"
#include "display/stereo.h"

namespace ddish::display {

class ProfileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class CameraModel { Single, Stereo, LightField, Grid };
const char* to_string(CameraModel model);

struct Profile {
  std::string name;
  std::string description;
  std::filesystem::path path;  // the file it came from; empty when parsed from text
  int views = 1;
  QuiltLayout layout;    // tile = one view's pixels; atlas = the quilt / side-by-side image
  float aspect = 1.0f;   // display aspect (width / height) the projections use
  CameraModel model = CameraModel::Single;
  LightFieldParams lightfield;  // model == LightField (lightfield.views == views)
  StereoParams stereo;          // model == Stereo
  GridParams grid;              // model == Grid
  // The panel's native resolution (Looking Glass devices): the size of the lenticular panel
  // image, which a device's calibration (visual.json: screenW × screenH) must match, and what
  // `ddish render --window --fullscreen` shows 1:1 on the panel's monitor.
  struct Panel {
    int width = 0;
    int height = 0;
  };
  std::optional<Panel> panel;
  std::optional<double> refresh_hz;
  std::optional<double> frame_budget_ms;

  // The per-frame budget: frame_budget_ms if given, else one refresh period, else none.
  std::optional<double> budget_ms() const;
};

// Parses a profile from JSON text; `source` names it in errors. Throws ProfileError.
Profile parse_profile(const std::string& json_text, const std::string& source);

// Reads a profile file. Throws ProfileError naming the file.
Profile load_profile_file(const std::filesystem::path& path);

// A profile by name ("looking-glass-portrait" → DISPLAYS_DIR/looking-glass-portrait.json) or by
// path (anything with a '/' or ending in ".json"). Throws ProfileError; an unknown name lists the
// profiles that exist.
Profile load_profile(const std::string& name_or_path);

// The folder profiles are looked up in: $DDISH_DISPLAYS_DIR if set and non-empty, else the
// source tree's displays/.
std::filesystem::path displays_dir();

// The names of the profiles in displays_dir(), sorted.
std::vector<std::string> profile_names();

}  // namespace ddish::display
