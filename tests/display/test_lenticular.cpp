// Lenticular interleaving against the published subpixel mapping, computed here independently.
#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "display/lenticular.h"
#include "display/quilt.h"

namespace ddish::display {
namespace {

// A small panel with Portrait-like lenticules: the screen is shrunk and the DPI with it, so the
// number of lenticules across the screen (pitch · screenW / DPI) stays the Portrait's.
std::string calibration_json(int inv_view, int flip_subp = 0) {
  return R"({"configVersion": "1.0", "serial": "TEST",
    "pitch": {"value": 52.58737671470091}, "slope": {"value": -7.196136200157333},
    "center": {"value": 0.4321881363063158}, "viewCone": {"value": 40.0},
    "invView": {"value": )" + std::to_string(inv_view) + R"(},
    "verticalAngle": {"value": 0.0}, "DPI": {"value": 63.28125},
    "screenW": {"value": 300.0}, "screenH": {"value": 400.0},
    "flipImageX": {"value": 0.0}, "flipImageY": {"value": 0.0},
    "flipSubp": {"value": )" + std::to_string(flip_subp) + "}}";
}

// The mapping written out from the published formula, independently of lenticular.cpp.
int expected_view(int x, int row, int sample, int views, bool inv) {
  const double W = 300.0, H = 400.0, dpi = 63.28125, slope = -7.196136200157333;
  const double pitch = 52.58737671470091 * (W / dpi) * std::cos(std::atan(1.0 / slope));
  const double tilt = H / (W * slope);
  const double subp = 1.0 / (3.0 * W);
  const double u = (x + 0.5) / W;
  const double v = 1.0 - (row + 0.5) / H;
  const double a = (u + sample * subp + v * tilt) * pitch - 0.4321881363063158;
  double phase = a - std::floor(a);
  if (inv) phase = 1.0 - phase;
  return std::min(static_cast<int>(std::floor(phase * views)), views - 1);
}

// An 8 × 6 quilt of 12 × 16 tiles where every pixel of view k is (k, 100 + k, 200 + k).
struct FlatQuilt {
  QuiltLayout layout = layout_from_tiles(8, 6, 12, 16);
  RgbImage image;
  FlatQuilt() {
    std::vector<std::vector<float>> data;
    std::vector<ConstRgbView> views;
    for (int k = 0; k < 48; ++k) {
      std::vector<float> d(3 * 12 * 16);
      for (std::size_t i = 0; i < d.size(); i += 3) {
        d[i] = float(k);
        d[i + 1] = 100.0f + float(k);
        d[i + 2] = 200.0f + float(k);
      }
      data.push_back(std::move(d));
    }
    for (const auto& d : data) views.push_back(ConstRgbView{12, 16, d.data()});
    image = compose_quilt(views, layout);
  }
};

TEST(Lenticular, CalibrationTermsFollowThePublishedFormulas) {
  const Calibration c = parse_calibration(calibration_json(1), "cal.json");
  EXPECT_EQ(c.screen_width, 300);
  EXPECT_TRUE(c.inv_view);
  ASSERT_TRUE(c.view_cone_deg.has_value());
  EXPECT_DOUBLE_EQ(*c.view_cone_deg, 40.0);
  const LenticularMapping m = lenticular_mapping(c);
  const double slope = -7.196136200157333;
  EXPECT_NEAR(m.pitch, 52.58737671470091 * 300.0 / 63.28125 * std::cos(std::atan(1.0 / slope)),
              1e-9);
  EXPECT_NEAR(m.tilt, 400.0 / (300.0 * slope), 1e-12);
  EXPECT_NEAR(m.subp, 1.0 / 900.0, 1e-15);
}

TEST(Lenticular, InterleavedSubpixelsShowTheViewTheMappingNames) {
  const FlatQuilt q;
  for (int inv : {0, 1}) {
    const LenticularMapping m = lenticular_mapping(parse_calibration(calibration_json(inv), "c"));
    const RgbImage panel = interleave(q.image.view(), q.layout, 48, m);
    ASSERT_EQ(panel.width(), 300);
    ASSERT_EQ(panel.height(), 400);
    for (auto [x, row] : {std::pair{0, 0}, {1, 0}, {150, 200}, {299, 399}, {37, 311}, {222, 5}}) {
      for (int c = 0; c < 3; ++c) {
        const int view = expected_view(x, row, c, 48, inv == 1);
        EXPECT_EQ(subpixel_view(m, x, row, c, 48), view) << x << "," << row << " ch " << c;
        EXPECT_NEAR(panel.pixel(x, row)[c], 100.0f * c + view, 1e-3f)
            << "pixel " << x << "," << row << " channel " << c << " invView " << inv;
      }
    }
    // Every subpixel agrees with the formula, and the slanted lenticules show every view.
    std::set<int> seen;
    int mismatches = 0;
    for (int row = 0; row < 400; ++row) {
      for (int x = 0; x < 300; ++x) {
        for (int c = 0; c < 3; ++c) {
          const int view = expected_view(x, row, c, 48, inv == 1);
          seen.insert(view);
          if (std::abs(panel.pixel(x, row)[c] - (100.0f * c + view)) > 1e-3f) ++mismatches;
        }
      }
    }
    EXPECT_EQ(mismatches, 0);
    EXPECT_EQ(seen.size(), 48u);
  }
}

TEST(Lenticular, InvViewReversesTheViewOrder) {
  const LenticularMapping plain = lenticular_mapping(parse_calibration(calibration_json(0), "c"));
  const LenticularMapping inverted =
      lenticular_mapping(parse_calibration(calibration_json(1), "c"));
  int checked = 0;
  for (int row = 0; row < 400; row += 7) {
    for (int x = 0; x < 300; x += 5) {
      for (int c = 0; c < 3; ++c) {
        const double scaled = subpixel_phase(plain, x, row, c) * 48.0;
        if (std::abs(scaled - std::round(scaled)) < 1e-6) continue;  // on a view boundary
        EXPECT_EQ(subpixel_view(inverted, x, row, c, 48), 47 - subpixel_view(plain, x, row, c, 48));
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 3000);
}

TEST(Lenticular, FlipSubpSwapsRedAndBlue) {
  const LenticularMapping rgb = lenticular_mapping(parse_calibration(calibration_json(0, 0), "c"));
  const LenticularMapping bgr = lenticular_mapping(parse_calibration(calibration_json(0, 1), "c"));
  for (auto [x, row] : {std::pair{3, 4}, {100, 250}, {299, 0}}) {
    EXPECT_EQ(subpixel_view(bgr, x, row, 0, 48), subpixel_view(rgb, x, row, 2, 48));
    EXPECT_EQ(subpixel_view(bgr, x, row, 2, 48), subpixel_view(rgb, x, row, 0, 48));
    EXPECT_EQ(subpixel_view(bgr, x, row, 1, 48), subpixel_view(rgb, x, row, 1, 48));
  }
}

TEST(Lenticular, BadCalibrationsGetOneLine) {
  EXPECT_THROW(parse_calibration("{", "c.json"), CalibrationError);
  try {
    parse_calibration(R"({"pitch": 50, "center": 0.1, "DPI": 300, "screenW": 10, "screenH": 10})",
                      "c.json");
    FAIL() << "no error";
  } catch (const CalibrationError& e) {
    EXPECT_STREQ(e.what(), "c.json: field 'slope' is missing");
  }
  EXPECT_THROW(parse_calibration(R"({"pitch": 50, "slope": 0, "center": 0.1, "DPI": 300,
                                     "screenW": 10, "screenH": 10})", "c.json"),
               CalibrationError);
  EXPECT_THROW(parse_calibration(R"({"pitch": {"value": "x"}, "slope": 5, "center": 0.1,
                                     "DPI": 300, "screenW": 10, "screenH": 10})", "c.json"),
               CalibrationError);
  EXPECT_THROW(load_calibration("/nonexistent/visual.json"), CalibrationError);
}

}  // namespace
}  // namespace ddish::display
