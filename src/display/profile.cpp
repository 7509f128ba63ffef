#include "display/profile.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <initializer_list>
#include <sstream>

#include <nlohmann/json.hpp>

#ifndef DDISH_DISPLAYS_DIR
#error "DDISH_DISPLAYS_DIR must name the source tree's displays/ folder (src/display/CMakeLists.txt)"
#endif

namespace ddish::display {

namespace {

using nlohmann::json;

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

// Reads the fields of one JSON object, naming the offending field ("quilt.columns") in every
// error, and remembers which keys were read so that unknown (misspelt) ones can be refused.
class Fields {
 public:
  Fields(const json& object, std::string source, std::string prefix)
      : object_(object), source_(std::move(source)), prefix_(std::move(prefix)) {
    if (!object_.is_object()) fail(prefix_.empty() ? "the profile" : where(""), "must be an object");
  }

  bool has(const std::string& key) {
    seen_.push_back(key);
    return object_.contains(key);
  }

  const json& object(const std::string& key) {
    if (!has(key)) fail(where(key), "is missing");
    return object_.at(key);
  }

  std::string text(const std::string& key, std::optional<std::string> fallback = {}) {
    if (!has(key)) return require(key, fallback);
    const json& v = object_.at(key);
    if (!v.is_string()) fail(where(key), "must be a string");
    return v.get<std::string>();
  }

  int integer(const std::string& key, std::optional<int> fallback = {}) {
    if (!has(key)) return require(key, fallback);
    const json& v = object_.at(key);
    if (!v.is_number_integer()) fail(where(key), "must be an integer");
    const auto i = v.get<long long>();
    if (i <= 0 || i > 1000000) fail(where(key), "must be between 1 and 1000000");
    return static_cast<int>(i);
  }

  double number(const std::string& key, std::optional<double> fallback = {}) {
    if (!has(key)) return require(key, fallback);
    const json& v = object_.at(key);
    if (!v.is_number()) fail(where(key), "must be a number");
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail(where(key), "must be finite");
    return d;
  }

  double positive(const std::string& key, std::optional<double> fallback = {}) {
    const double d = number(key, fallback);
    if (!(d > 0.0)) fail(where(key), "must be positive");
    return d;
  }

  std::optional<double> optional_positive(const std::string& key) {
    if (!has(key)) return std::nullopt;
    return positive(key);
  }

  bool boolean(const std::string& key, bool fallback) {
    if (!has(key)) return fallback;
    const json& v = object_.at(key);
    if (!v.is_boolean()) fail(where(key), "must be true or false");
    return v.get<bool>();
  }

  // Refuses keys that were never asked for.
  void finish() const {
    for (const auto& item : object_.items()) {
      if (std::find(seen_.begin(), seen_.end(), item.key()) == seen_.end()) {
        fail(where(item.key()), "is not a known field");
      }
    }
  }

  std::string where(const std::string& key) const {
    if (key.empty()) return "field '" + prefix_ + "'";
    return "field '" + (prefix_.empty() ? key : prefix_ + "." + key) + "'";
  }

  [[noreturn]] void fail(const std::string& what, const std::string& problem) const {
    throw ProfileError(source_ + ": " + what + " " + problem);
  }

  const std::string& source() const { return source_; }
  std::string child(const std::string& key) const {
    return prefix_.empty() ? key : prefix_ + "." + key;
  }

 private:
  template <typename T>
  T require(const std::string& key, const std::optional<T>& fallback) const {
    if (!fallback) fail(where(key), "is missing");
    return *fallback;
  }

  const json& object_;
  std::string source_;
  std::string prefix_;
  std::vector<std::string> seen_;
};

EyeFov read_eye_fov(Fields& parent, const std::string& key) {
  Fields f(parent.object(key), parent.source(), parent.child(key));
  EyeFov fov;
  fov.left = static_cast<float>(f.number("left") * kDegToRad);
  fov.right = static_cast<float>(f.number("right") * kDegToRad);
  fov.up = static_cast<float>(f.number("up") * kDegToRad);
  fov.down = static_cast<float>(f.number("down") * kDegToRad);
  f.finish();
  return fov;
}

// The camera object; also checks that the model agrees with the view count.
void read_camera(Fields& top, Profile& p) {
  Fields f(top.object("camera"), top.source(), "camera");
  const std::string model = f.text("model");
  try {
    if (model == "single") {
      p.model = CameraModel::Single;
      if (p.views != 1) f.fail("field 'views'", "must be 1 for the single camera model");
    } else if (model == "stereo") {
      p.model = CameraModel::Stereo;
      if (p.views != 2) f.fail("field 'views'", "must be 2 for the stereo camera model");
      p.stereo.ipd = static_cast<float>(f.number("ipd_mm", 63.0) / 1000.0);
      p.stereo.converge = f.boolean("converge", true);
      if (auto d = f.optional_positive("convergence_distance")) {
        p.stereo.convergence_distance = static_cast<float>(*d);
      }
      if (f.has("eye_fov_deg")) {
        Fields eyes(f.object("eye_fov_deg"), f.source(), "camera.eye_fov_deg");
        p.stereo.left_eye_fov = read_eye_fov(eyes, "left");
        p.stereo.right_eye_fov = read_eye_fov(eyes, "right");
        eyes.finish();
      }
      p.stereo.validate();
    } else if (model == "lightfield") {
      p.model = CameraModel::LightField;
      p.lightfield.views = p.views;
      p.lightfield.view_cone = static_cast<float>(f.number("view_cone_deg", 40.0) * kDegToRad);
      if (auto d = f.optional_positive("focal_distance")) {
        p.lightfield.focal_distance = static_cast<float>(*d);
      }
      if (auto fov = f.optional_positive("fov_deg")) {
        p.lightfield.fov_y = static_cast<float>(*fov * kDegToRad);
      }
      p.lightfield.validate();
    } else if (model == "grid") {
      p.model = CameraModel::Grid;
      p.grid.columns = f.integer("columns");
      p.grid.rows = f.integer("rows");
      if (p.grid.columns * p.grid.rows != p.views) {
        f.fail("field 'views'", "must equal camera.columns x camera.rows");
      }
      if (f.has("spacing")) {
        const double s = f.number("spacing");
        if (s < 0.0) f.fail(f.where("spacing"), "must be >= 0");
        p.grid.spacing = static_cast<float>(s);
      }
      p.grid.spacing_ratio = static_cast<float>(f.number("spacing_ratio", p.grid.spacing_ratio));
      if (auto d = f.optional_positive("recenter_distance")) {
        p.grid.recenter_distance = static_cast<float>(*d);
      }
      p.grid.validate();
    } else {
      f.fail(f.where("model"), "must be one of single, stereo, lightfield, grid (got '" +
                                   model + "')");
    }
  } catch (const std::invalid_argument& e) {
    f.fail("camera:", e.what());
  }
  f.finish();
}

void read_layout(Fields& top, Profile& p) {
  Fields q(top.object("quilt"), top.source(), "quilt");
  const int columns = q.integer("columns");
  const int rows = q.integer("rows");
  const bool sized = q.has("width") || q.has("height");
  std::optional<QuiltLayout> from_atlas;
  if (sized) from_atlas = QuiltLayout{columns, rows, 0, 0, q.integer("width"), q.integer("height")};
  q.finish();

  std::optional<std::pair<int, int>> tile;
  if (top.has("tile")) {
    Fields t(top.object("tile"), top.source(), "tile");
    tile = std::pair{t.integer("width"), t.integer("height")};
    t.finish();
  }
  if (!from_atlas && !tile) {
    top.fail("field 'tile'", "is missing (give the tile size, the quilt size, or both)");
  }
  try {
    if (from_atlas) {
      p.layout = layout_from_atlas(columns, rows, from_atlas->width, from_atlas->height);
      if (tile && (tile->first != p.layout.tile_width || tile->second != p.layout.tile_height)) {
        top.fail("field 'tile'", std::to_string(tile->first) + "x" +
                                     std::to_string(tile->second) + " disagrees with quilt " +
                                     std::to_string(p.layout.width) + "x" +
                                     std::to_string(p.layout.height) + " / " +
                                     std::to_string(columns) + "x" + std::to_string(rows) +
                                     " = " + std::to_string(p.layout.tile_width) + "x" +
                                     std::to_string(p.layout.tile_height));
      }
    } else {
      p.layout = layout_from_tiles(columns, rows, tile->first, tile->second);
    }
  } catch (const std::invalid_argument& e) {
    top.fail("field 'quilt':", e.what());
  }
  if (p.views > p.layout.cells()) {
    top.fail("field 'views'", std::to_string(p.views) + " does not fit a " +
                                  std::to_string(columns) + "x" + std::to_string(rows) + " quilt");
  }
}

}  // namespace

const char* to_string(CameraModel model) {
  switch (model) {
    case CameraModel::Single: return "single";
    case CameraModel::Stereo: return "stereo";
    case CameraModel::LightField: return "lightfield";
    case CameraModel::Grid: return "grid";
  }
  return "unknown";
}

std::optional<double> Profile::budget_ms() const {
  if (frame_budget_ms) return frame_budget_ms;
  if (refresh_hz) return 1000.0 / *refresh_hz;
  return std::nullopt;
}

Profile parse_profile(const std::string& json_text, const std::string& source) {
  json doc;
  try {
    doc = json::parse(json_text);
  } catch (const json::parse_error& e) {
    // nlohmann's message is one line and says where ("at line 3, column 5").
    throw ProfileError(source + ": not valid JSON: " + e.what());
  }
  Fields top(doc, source, "");
  Profile p;
  p.name = top.text("name");
  if (p.name.empty()) top.fail(top.where("name"), "must not be empty");
  p.description = top.text("description", std::string());
  p.views = top.integer("views");
  read_layout(top, p);
  p.aspect = static_cast<float>(
      top.positive("aspect", double(p.layout.tile_width) / double(p.layout.tile_height)));
  read_camera(top, p);
  if (top.has("panel")) {
    Fields panel(top.object("panel"), top.source(), "panel");
    p.panel = Profile::Panel{panel.integer("width"), panel.integer("height")};
    panel.finish();
  }
  p.refresh_hz = top.optional_positive("refresh_hz");
  p.frame_budget_ms = top.optional_positive("frame_budget_ms");
  top.finish();
  return p;
}

Profile load_profile_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ProfileError(path.string() + ": cannot open display profile");
  std::ostringstream text;
  text << in.rdbuf();
  Profile p = parse_profile(text.str(), path.string());
  p.path = path;
  return p;
}

std::filesystem::path displays_dir() {
  const char* env = std::getenv("DDISH_DISPLAYS_DIR");
  if (env != nullptr && env[0] != '\0') return std::filesystem::path(env);
  return std::filesystem::path(DDISH_DISPLAYS_DIR);
}

std::vector<std::string> profile_names() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(displays_dir(), ec)) {
    if (entry.is_regular_file() && entry.path().extension() == ".json") {
      names.push_back(entry.path().stem().string());
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

Profile load_profile(const std::string& name_or_path) {
  const bool is_path = name_or_path.find('/') != std::string::npos ||
                       std::filesystem::path(name_or_path).extension() == ".json";
  if (is_path) return load_profile_file(name_or_path);

  const std::filesystem::path file = displays_dir() / (name_or_path + ".json");
  if (!std::filesystem::is_regular_file(file)) {
    std::string known;
    for (const auto& n : profile_names()) known += (known.empty() ? "" : ", ") + n;
    throw ProfileError("unknown display profile '" + name_or_path + "' (looked in " +
                       displays_dir().string() + "; available: " +
                       (known.empty() ? "none" : known) + ")");
  }
  return load_profile_file(file);
}

}  // namespace ddish::display
