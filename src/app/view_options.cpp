#include "app/view_options.h"

#include <cmath>
#include <optional>
#include <stdexcept>
#include <tuple>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "display/profile_views.h"
#include "scene/scene.h"

namespace ddish::app {

void add_display_options(CLI::App& cmd, DisplayArgs& args) {
  DisplayArgs* a = &args;
  cmd.add_option("--display", args.display,
                 "single (default), stereo (the stereo-hmd profile), or a display profile: a name "
                 "in displays/ (e.g. looking-glass-portrait) or a .json path; `--display list` "
                 "lists the profiles");
  cmd.add_option_function<int>(
      "--views", [a](int n) { a->views = n; },
      "number of views: any N for a light-field profile (quilt layout recomputed unless N is "
      "the profile's), else it must equal the profile's");
  cmd.add_option_function<float>(
      "--focal-distance", [a](float m) { a->focal_distance = m; },
      "distance from the camera to the zero-parallax plane (default: to the scene's centre)");
}

std::string display_list() {
  std::string text;
  for (const std::string& name : display::profile_names()) {
    try {
      const display::Profile p = display::load_profile(name);
      text += fmt::format("{:28} {:3} views  quilt {}x{} of {}x{}, tiles {}x{}", p.name, p.views,
                          p.layout.columns, p.layout.rows, p.layout.width, p.layout.height,
                          p.layout.tile_width, p.layout.tile_height);
      if (p.panel) text += fmt::format(", panel {}x{}", p.panel->width, p.panel->height);
      text += '\n';
    } catch (const display::ProfileError& e) {
      text += fmt::format("{:28} (broken: {})\n", name, e.what());
    }
  }
  return text;
}

display::QuiltLayout choose_quilt_layout(int views, int tile_width, int tile_height) {
  if (views < 1 || tile_width < 1 || tile_height < 1)
    throw std::invalid_argument(fmt::format("a quilt of {} views of {}x{} is empty", views,
                                            tile_width, tile_height));
  // Lexicographic score: empty cells, distance from a square atlas (log of its aspect, so 2:1
  // and 1:2 are equally far), then more columns (a wide quilt keeps the rig's left-to-right order
  // in one row as long as possible).
  std::tuple<int, double, int> best{0, 0.0, 0};
  std::optional<display::QuiltLayout> chosen;
  for (int rows = 1; rows <= views; ++rows) {
    const int columns = (views + rows - 1) / rows;
    const long long width = static_cast<long long>(columns) * tile_width;
    const long long height = static_cast<long long>(rows) * tile_height;
    if (width > kMaxAtlasSide || height > kMaxAtlasSide) continue;
    const std::tuple<int, double, int> score{columns * rows - views,
                                             std::fabs(std::log(double(width) / double(height))),
                                             -columns};
    if (!chosen || score < best) {
      best = score;
      chosen = display::layout_from_tiles(columns, rows, tile_width, tile_height);
    }
  }
  if (!chosen)
    throw std::invalid_argument(fmt::format(
        "{} views of {}x{} do not fit a quilt of at most {}x{} pixels (use fewer views or a "
        "smaller --width/--height)",
        views, tile_width, tile_height, kMaxAtlasSide, kMaxAtlasSide));
  return *chosen;
}

namespace {

display::Profile load_display_profile(const std::string& name) {
  try {
    return display::load_profile(name == "stereo" ? "stereo-hmd" : name);
  } catch (const display::ProfileError& e) {
    throw display::ProfileError(fmt::format("--display: {}; or single, stereo", e.what()));
  }
}

// How many views the profile's camera model can take, or an error naming the model.
void check_view_count(const display::Profile& p, int views) {
  if (p.model == display::CameraModel::LightField || views == p.views) return;
  throw std::invalid_argument(fmt::format(
      "--views {}: display '{}' is a {} camera with {} views; only light-field profiles take "
      "another count",
      views, p.name, display::to_string(p.model), p.views));
}

}  // namespace

DisplayChoice resolve_display(const DisplayArgs& d, const CameraArgs& camera) {
  if (d.views && *d.views < 1)
    throw std::invalid_argument(fmt::format("--views must be at least 1, got {}", *d.views));
  if (d.focal_distance && !(*d.focal_distance > 0.0f && std::isfinite(*d.focal_distance)))
    throw std::invalid_argument(
        fmt::format("--focal-distance must be positive, got {:g}", *d.focal_distance));
  DisplayChoice choice;
  if (d.display.empty() || d.display == "single") {
    if (d.views && *d.views != 1)
      throw std::invalid_argument(fmt::format(
          "--views {}: the single display has one view; give a light-field --display such as "
          "looking-glass-portrait",
          *d.views));
    return choice;
  }

  display::Profile p = load_display_profile(d.display);
  const int views = d.views.value_or(p.views);
  check_view_count(p, views);
  const int tile_width = camera.width_given ? camera.width : p.layout.tile_width;
  const int tile_height = camera.height_given ? camera.height : p.layout.tile_height;
  const bool same_tiles = tile_width == p.layout.tile_width && tile_height == p.layout.tile_height;
  if (views != p.views) {
    p.layout = choose_quilt_layout(views, tile_width, tile_height);
  } else if (!same_tiles) {
    // The profile's columns × rows with the new tiles; its atlas size (which may have spare
    // pixels, looking-glass-16) belongs to its own tile size.
    p.layout = display::layout_from_tiles(p.layout.columns, p.layout.rows, tile_width, tile_height);
    if (p.layout.width > kMaxAtlasSide || p.layout.height > kMaxAtlasSide)
      throw std::invalid_argument(fmt::format("a {}x{} quilt of {}x{} tiles exceeds {}x{} pixels",
                                              p.layout.columns, p.layout.rows, tile_width,
                                              tile_height, kMaxAtlasSide, kMaxAtlasSide));
  }
  p.views = views;
  p.lightfield.views = views;
  // The command line wins over a focal plane fixed by the profile.
  if (d.focal_distance && p.model == display::CameraModel::LightField)
    p.lightfield.focal_distance = d.focal_distance;
  choice.profile = std::move(p);
  return choice;
}

float view_aspect(const DisplayChoice& choice, const CameraArgs& camera) {
  if (choice.single()) return float(camera.width) / float(camera.height);
  const display::QuiltLayout& l = choice.profile->layout;
  return float(l.tile_width) / float(l.tile_height);
}

display::ViewSet make_frame_views(const scene::Scene& scene, const DisplayChoice& choice,
                                  const DisplayArgs& display, const CameraArgs& camera) {
  return make_frame_views(scene, choice, display, camera, resolve_camera(scene, camera));
}

display::ViewSet make_frame_views(const scene::Scene& scene, const DisplayChoice& choice,
                                  const DisplayArgs& display, const CameraArgs& camera,
                                  const scene::Camera& c) {
  if (choice.single()) {
    // Exactly the single view `ddish render` always drew, so existing outputs do not move.
    display::ViewSet set;
    set.kind = display::ViewSetKind::Single;
    set.name = "single";
    set.views = {scene::camera_view(c, camera.width, camera.height)};
    set.layout = display::layout_from_tiles(1, 1, camera.width, camera.height);
    set.aspect = float(camera.width) / float(camera.height);
    return set;
  }
  const float focal = display.focal_distance.value_or(
      display::focal_distance_to_scene_center(scene, c.eye, c.forward));
  return display::make_view_set(*choice.profile, display::base_camera(c, focal));
}

}  // namespace ddish::app
