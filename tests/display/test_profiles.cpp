// Display profiles: the shipped ones load with the numbers they promise, bad ones fail with one
// line naming the field, lookup by name / path / environment, and the view sets they build.
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "display/profile.h"
#include "display/profile_views.h"
#include "display/quilt.h"
#include "projection.h"

namespace ddish::display {
namespace {

namespace fs = std::filesystem;

const fs::path kDisplays = fs::path(DDISH_SOURCE_DIR) / "displays";

BaseCamera camera() {
  BaseCamera b;
  b.eye = glm::vec3(0.0f, 1.0f, 4.0f);
  b.forward = glm::vec3(0.0f, 0.0f, -1.0f);
  b.fov_y = glm::radians(45.0f);
  b.focal_distance = 4.0f;
  return b;
}

TEST(Profiles, EveryShippedProfileLoadsAndBuildsItsViews) {
  const std::vector<std::string> names = profile_names();
  for (const char* expected : {"lightfield-32x720p", "looking-glass-16", "looking-glass-portrait",
                               "single-1080p", "stereo-hmd"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
  }
  for (const std::string& name : names) {
    const Profile p = load_profile(name);
    EXPECT_EQ(p.name, name);
    const ViewSet set = make_view_set(p, camera());
    EXPECT_EQ(static_cast<int>(set.size()), p.views) << name;
    EXPECT_EQ(set.name, name);
    for (const scene::View& v : set.views) {
      EXPECT_EQ(v.width, p.layout.tile_width) << name;
      EXPECT_EQ(v.height, p.layout.tile_height) << name;
    }
  }
}

TEST(Profiles, LookingGlassPortrait) {
  const Profile p = load_profile("looking-glass-portrait");
  EXPECT_EQ(p.views, 48);
  EXPECT_EQ(p.model, CameraModel::LightField);
  EXPECT_EQ(p.layout.columns, 8);
  EXPECT_EQ(p.layout.rows, 6);
  EXPECT_EQ(p.layout.width, 3360);
  EXPECT_EQ(p.layout.height, 3360);
  EXPECT_EQ(p.layout.tile_width, 420);
  EXPECT_EQ(p.layout.tile_height, 560);
  EXPECT_FLOAT_EQ(p.aspect, 0.75f);
  EXPECT_NEAR(p.lightfield.view_cone, glm::radians(40.0f), 1e-6f);
  EXPECT_FALSE(p.budget_ms().has_value());
  EXPECT_EQ(quilt_file_name("cornell", p.layout, p.aspect), "cornell_qs8x6a0.75.png");
  const RgbImage quilt = compose_quilt(std::span<const ConstRgbView>(), p.layout);
  EXPECT_EQ(quilt.width(), 3360);
  EXPECT_EQ(quilt.height(), 3360);
}

TEST(Profiles, LookingGlass16RoundsTilesDown) {
  const Profile p = load_profile("looking-glass-16");
  EXPECT_EQ(p.views, 45);
  EXPECT_EQ(p.layout.columns, 5);
  EXPECT_EQ(p.layout.rows, 9);
  EXPECT_EQ(p.layout.width, 4096);
  EXPECT_EQ(p.layout.tile_width, 819);   // 4096 / 5 = 819.2
  EXPECT_EQ(p.layout.tile_height, 455);  // 4096 / 9 = 455.1
  EXPECT_EQ(quilt_file_name("room", p.layout, p.aspect), "room_qs5x9a1.77.png");
}

TEST(Profiles, LightField32x720pIsAnEightByFourGrid) {
  const Profile p = load_profile("lightfield-32x720p");
  EXPECT_EQ(p.views, 32);
  EXPECT_EQ(p.model, CameraModel::Grid);
  EXPECT_EQ(p.grid.columns, 8);
  EXPECT_EQ(p.grid.rows, 4);
  EXPECT_EQ(p.layout.width, 10240);
  EXPECT_EQ(p.layout.height, 2880);
  EXPECT_NEAR(p.aspect, 1280.0f / 720.0f, 1e-6f);
}

TEST(Profiles, StereoHmd) {
  const Profile p = load_profile("stereo-hmd");
  EXPECT_EQ(p.model, CameraModel::Stereo);
  EXPECT_EQ(p.views, 2);
  EXPECT_EQ(p.layout.tile_width, 1440);
  EXPECT_EQ(p.layout.tile_height, 1600);
  EXPECT_NEAR(p.stereo.ipd, 0.063f, 1e-7f);
  ASSERT_TRUE(p.stereo.left_eye_fov && p.stereo.right_eye_fov);
  EXPECT_NEAR(p.stereo.left_eye_fov->left, glm::radians(-50.0f), 1e-6f);
  EXPECT_NEAR(p.stereo.right_eye_fov->right, glm::radians(50.0f), 1e-6f);
  ASSERT_TRUE(p.budget_ms().has_value());
  EXPECT_NEAR(*p.budget_ms(), 11.111, 1e-3);  // 90 Hz
  const ViewSet set = make_view_set(p, camera());
  EXPECT_NEAR(glm::length(set.views[1].eye() - set.views[0].eye()), 0.063f, 1e-6f);
}

TEST(Profiles, Single1080p) {
  const Profile p = load_profile("single-1080p");
  EXPECT_EQ(p.model, CameraModel::Single);
  EXPECT_EQ(p.layout.tile_width, 1920);
  EXPECT_EQ(p.layout.tile_height, 1080);
  const ViewSet set = make_view_set(p, camera());
  // Straight ahead is the centre pixel.
  const glm::dvec2 c = test::project_point(set.views[0], glm::vec3(0.0f, 1.0f, 0.0f));
  EXPECT_NEAR(c.x, 960.0, 1e-3);
  EXPECT_NEAR(c.y, 540.0, 1e-3);
}

TEST(Profiles, LookupByPathAndByEnvironmentFolder) {
  const Profile by_path = load_profile((kDisplays / "single-1080p.json").string());
  EXPECT_EQ(by_path.name, "single-1080p");
  EXPECT_EQ(by_path.path, kDisplays / "single-1080p.json");

  const fs::path dir = fs::temp_directory_path() / "ddish_display_profiles_test";
  fs::create_directories(dir);
  std::ofstream(dir / "tiny.json") << R"({"name": "tiny", "views": 1,
    "quilt": {"columns": 1, "rows": 1}, "tile": {"width": 8, "height": 4},
    "camera": {"model": "single"}})";
  ::setenv("DDISH_DISPLAYS_DIR", dir.c_str(), 1);
  EXPECT_EQ(displays_dir(), dir);
  const Profile tiny = load_profile("tiny");
  EXPECT_EQ(tiny.layout.tile_width, 8);
  EXPECT_FLOAT_EQ(tiny.aspect, 2.0f);  // defaults to the tile's
  EXPECT_THROW(load_profile("looking-glass-portrait"), ProfileError);
  ::unsetenv("DDISH_DISPLAYS_DIR");
  fs::remove_all(dir);
  EXPECT_EQ(displays_dir(), kDisplays);
}

// The one-line message a bad profile gets.
std::string error_of(const std::string& json) {
  try {
    parse_profile(json, "bad.json");
  } catch (const ProfileError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Profiles, BadProfilesGetOneLineNamingTheField) {
  const std::string good_rest = R"("quilt": {"columns": 2, "rows": 1}, "tile": {"width": 8,
      "height": 8}, "camera": {"model": "stereo"})";
  struct Case {
    std::string json;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"{", "bad.json: not valid JSON"},
      {"[1, 2]", "bad.json: the profile must be an object"},
      {R"({"views": 2, )" + good_rest + "}", "field 'name' is missing"},
      {R"({"name": "x", "views": "2", )" + good_rest + "}", "field 'views' must be an integer"},
      {R"({"name": "x", "views": 3, "quilt": {"columns": 3, "rows": 1}, "tile": {"width": 8,
          "height": 8}, "camera": {"model": "stereo"}})",
       "field 'views' must be 2"},
      {R"({"name": "x", "views": 2, "colour": 1, )" + good_rest + "}",
       "field 'colour' is not a known field"},
      {R"({"name": "x", "views": 2, "quilt": {"columns": 2, "rows": 1}, "camera": {"model":
          "stereo"}})",
       "field 'tile' is missing"},
      {R"({"name": "x", "views": 2, "quilt": {"columns": 2, "rows": 1, "width": 17}, "tile":
          {"width": 8, "height": 8}, "camera": {"model": "stereo"}})",
       "field 'quilt.height' is missing"},
      {R"({"name": "x", "views": 48, "quilt": {"columns": 8, "rows": 6, "width": 3360, "height":
          3360}, "tile": {"width": 400, "height": 560}, "camera": {"model": "lightfield"}})",
       "field 'tile' 400x560 disagrees with quilt 3360x3360 / 8x6 = 420x560"},
      {R"({"name": "x", "views": 2, )" + good_rest.substr(0, good_rest.find("\"camera\"")) +
           R"("camera": {"model": "fisheye"}})",
       "field 'camera.model' must be one of single, stereo, lightfield, grid"},
      {R"({"name": "x", "views": 2, "quilt": {"columns": 2, "rows": 1}, "tile": {"width": 8,
          "height": 8}, "camera": {"model": "stereo", "ipd_mm": -3}})",
       "camera: stereo IPD"},
      {R"({"name": "x", "views": 2, "quilt": {"columns": 2, "rows": 1}, "tile": {"width": 8,
          "height": 8}, "camera": {"model": "stereo", "eye_fov_deg": {"left": {"left": -40,
          "right": 40, "up": 40}}}})",
       "field 'camera.eye_fov_deg.left.down' is missing"},
      {R"({"name": "x", "views": 9, "quilt": {"columns": 2, "rows": 1}, "tile": {"width": 8,
          "height": 8}, "camera": {"model": "lightfield"}})",
       "field 'views' 9 does not fit a 2x1 quilt"},
      {R"({"name": "x", "views": 2, )" + good_rest + R"(, "refresh_hz": 0})",
       "field 'refresh_hz' must be positive"},
  };
  for (const Case& c : cases) {
    const std::string message = error_of(c.json);
    EXPECT_NE(message.find(c.expected), std::string::npos)
        << "json: " << c.json << "\nmessage: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.rfind("bad.json: ", 0), 0u) << message;
  }
}

TEST(Profiles, MissingFilesAndUnknownNamesSayWhatExists) {
  try {
    load_profile("no-such-display");
    FAIL() << "no error";
  } catch (const ProfileError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("unknown display profile 'no-such-display'"), std::string::npos) << m;
    EXPECT_NE(m.find("looking-glass-portrait"), std::string::npos) << m;
  }
  EXPECT_THROW(load_profile("/nonexistent/dir/x.json"), ProfileError);
}

}  // namespace
}  // namespace ddish::display

namespace ddish::display {
namespace {

// Issue 16's device table (vendor documentation; per-view sizes from the Blender add-on's device
// table): quilt, views, tile, and the panel resolution each profile carries.
TEST(Profiles, EveryLookingGlassDeviceOfTheTable) {
  struct Device {
    const char* name;
    int columns, rows, views, tile_w, tile_h, panel_w, panel_h;
  };
  for (const Device& d : {Device{"looking-glass-portrait", 8, 6, 48, 420, 560, 1536, 2048},
                          Device{"looking-glass-go", 11, 6, 66, 372, 682, 1440, 2560},
                          Device{"looking-glass-16-landscape", 7, 7, 49, 857, 857, 3840, 2160},
                          Device{"looking-glass-16-portrait", 11, 6, 66, 545, 1000, 2160, 3840},
                          Device{"looking-glass-32-landscape", 7, 7, 49, 1170, 1170, 7680, 4320},
                          Device{"looking-glass-32-portrait", 11, 6, 66, 744, 1364, 4320, 7680},
                          Device{"looking-glass-65", 8, 9, 72, 1024, 910, 7680, 4320},
                          Device{"looking-glass-16", 5, 9, 45, 819, 455, 3840, 2160}}) {
    SCOPED_TRACE(d.name);
    const Profile p = load_profile(d.name);
    EXPECT_EQ(p.model, CameraModel::LightField);
    EXPECT_EQ(p.layout.columns, d.columns);
    EXPECT_EQ(p.layout.rows, d.rows);
    EXPECT_EQ(p.views, d.views);
    EXPECT_EQ(p.layout.tile_width, d.tile_w);
    EXPECT_EQ(p.layout.tile_height, d.tile_h);
    ASSERT_TRUE(p.panel.has_value());
    EXPECT_EQ(p.panel->width, d.panel_w);
    EXPECT_EQ(p.panel->height, d.panel_h);
    EXPECT_NEAR(p.aspect, float(d.panel_w) / float(d.panel_h), 1e-6f);  // the panel's aspect
  }
}

TEST(Profiles, PanelNeedsWholePositiveSizes) {
  const std::string base = R"({"name": "p", "views": 4, "quilt": {"columns": 2, "rows": 2},
    "tile": {"width": 8, "height": 8}, "camera": {"model": "lightfield"}, )";
  EXPECT_EQ(parse_profile(base + R"("panel": {"width": 30, "height": 40}})", "p.json").panel->height, 40);
  EXPECT_THROW(parse_profile(base + R"("panel": {"width": 0, "height": 40}})", "p.json"), ProfileError);
  EXPECT_THROW(parse_profile(base + R"("panel": {"width": 30}})", "p.json"), ProfileError);
  EXPECT_THROW(parse_profile(base + R"("panel": {"width": 30, "height": 40, "dpi": 3}})", "p.json"),
               ProfileError);
}

}  // namespace
}  // namespace ddish::display
