// The window's GPU composition (display/gpu_compositor.h) against the CPU outputs it replaces:
// the lenticular pass equals display::interleave byte for byte (tolerance 0: the shader takes the
// CPU's subpixel views, bilinear taps and sRGB tables and repeats its float arithmetic), for the
// Portrait and the 16-inch panels at their native resolution and for every flip flag; the atlas
// pass equals the quilt the file writer composes. Views are uploaded as packed RGBA8, the form
// raster::BatchViews::display hands them over in, gathered in two batches as the renderer would.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../gpu/gpu_test.h"
#include "status_text.h"
#include "display/gpu_compositor.h"
#include "display/lenticular.h"
#include "display/quilt.h"
#include "gpu/buffer.h"
#include "gpu/commands.h"
#include "gpu/transfer.h"
#include "metrics/color.h"

namespace ddish::display {
namespace {

using gpu::test::GpuTest;

std::vector<float> decoded_table() {
  std::vector<float> t(256);
  for (int c = 0; c < 256; ++c) t[std::size_t(c)] = metrics::srgb8_decode(std::uint8_t(c));
  return t;
}

// Calibrations of the usual magnitudes for the two panels (a unit's own visual.json differs a
// little in pitch, slope and center; what matters here is the panel size and the flags).
Calibration portrait(bool inv, bool fx, bool fy, bool subp) {
  Calibration c{.pitch = 52.58737671470091, .slope = -7.196136200157333,
                .center = 0.4321881363063158, .dpi = 324.0, .screen_width = 1536,
                .screen_height = 2048};
  c.inv_view = inv, c.flip_x = fx, c.flip_y = fy, c.flip_subpixels = subp;
  return c;
}
Calibration sixteen(bool inv, bool fx, bool fy, bool subp) {
  Calibration c{.pitch = 47.58, .slope = -5.49, .center = 0.09, .dpi = 283.0,
                .screen_width = 3840, .screen_height = 2160};
  c.inv_view = inv, c.flip_x = fx, c.flip_y = fy, c.flip_subpixels = subp;
  return c;
}
// A panel shrunk with its DPI, so the lenticules across it stay the Portrait's: for the flag
// combinations, which need no full-size panel each.
Calibration small(bool inv, bool fx, bool fy, bool subp) {
  Calibration c = portrait(inv, fx, fy, subp);
  c.screen_width = 300, c.screen_height = 400, c.dpi = 63.28125;
  return c;
}

// View k: a distinct flat colour, or (gradient) that colour plus ramps across the tile so that
// bilinear filtering between texels matters.
std::vector<std::uint32_t> make_views(int views, int w, int h, bool gradient) {
  std::vector<std::uint32_t> px(std::size_t(views) * std::size_t(w) * std::size_t(h));
  for (int k = 0; k < views; ++k)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        std::uint32_t r = std::uint32_t(5 * k) & 0xFF, g = std::uint32_t(255 - 5 * k) & 0xFF,
                      b = std::uint32_t(37 * k) & 0xFF;
        if (gradient) {
          r = (r + std::uint32_t(x * 255 / w)) & 0xFF;
          g = (g + std::uint32_t(y * 255 / h)) & 0xFF;
          b = (b + std::uint32_t((x * y) % 97)) & 0xFF;
        }
        px[(std::size_t(k) * std::size_t(h) + std::size_t(y)) * std::size_t(w) + std::size_t(x)] =
            r | (g << 8) | (b << 16) | 0xFF000000u;
      }
  return px;
}

// The quilt of the views' display values decoded to floats, as app/frame_outputs builds it.
RgbImage cpu_quilt(const std::vector<std::uint32_t>& px, int views, const QuiltLayout& layout) {
  const int w = layout.tile_width, h = layout.tile_height;
  std::vector<std::vector<float>> data{std::size_t(views)};
  std::vector<ConstRgbView> v;
  for (int k = 0; k < views; ++k) {
    auto& d = data[std::size_t(k)];
    d.resize(3 * std::size_t(w) * std::size_t(h));
    for (std::size_t i = 0; i < std::size_t(w) * std::size_t(h); ++i)
      for (std::size_t c = 0; c < 3; ++c)
        d[3 * i + c] = metrics::srgb8_decode(
            std::uint8_t(px[std::size_t(k) * std::size_t(w) * std::size_t(h) + i] >> (8 * c)));
    v.push_back(ConstRgbView{w, h, d.data()});
  }
  return compose_quilt(v, layout);
}

class GpuCompositorTest : public GpuTest {
 protected:
  // Uploads the views, gathers them in two batches, composes and reads the output back.
  // `setup` (optional) sets the compositor's overlay or text first; `composes` passes run on
  // the same gathered views (as the window's --hold does).
  std::vector<std::uint32_t> compose(const std::vector<std::uint32_t>& px, int views,
                                     const QuiltLayout& layout,
                                     const std::optional<LenticularMapping>& mapping,
                                     const std::function<void(GpuCompositor&)>& setup = {},
                                     int composes = 1) {
    const std::vector<float> decoded = decoded_table();
    GpuCompositor comp(device(), layout, views, mapping,
                       Srgb8Tables{std::span<const float, 256>(decoded.data(), 256),
                                   metrics::srgb8_midpoints()});
    if (setup) setup(comp);
    gpu::CommandRunner runner(device());
    gpu::Buffer input(device(), px.size() * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                      gpu::MemoryUse::upload);
    input.write(px.data(), px.size() * 4);
    const auto w = std::uint32_t(layout.tile_width), h = std::uint32_t(layout.tile_height);
    const std::uint32_t half = std::uint32_t(views) / 2;
    const std::size_t view_words = std::size_t(w) * h;
    // Batch 2 (views half..) first, from its own buffer, as a renderer's batch buffer holds
    // only its views.
    gpu::Buffer second(device(), (px.size() - half * view_words) * 4,
                       VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUse::upload);
    second.write(px.data() + half * view_words, second.size());
    runner.run([&](VkCommandBuffer cmd) {
      comp.record_gather(cmd, second, half, std::uint32_t(views) - half, w, h);
    });
    runner.run([&](VkCommandBuffer cmd) {
      if (half > 0) comp.record_gather(cmd, input, 0, half, w, h);  // one view: one batch
      comp.record_compose(cmd);
    });
    for (int k = 1; k < composes; ++k) runner.run([&](VkCommandBuffer cmd) { comp.record_compose(cmd); });
    return gpu::download<std::uint32_t>(device(), runner, comp.output(),
                                        std::size_t(comp.output_width()) * std::size_t(comp.output_height()));
  }

  // Counts bytes of the GPU panel that differ from the CPU interleave, and checks the size.
  int lenticular_mismatches(const Calibration& c, int views, int tw, int th, bool gradient) {
    const QuiltLayout layout = views == 48 ? layout_from_tiles(8, 6, tw, th) : layout_from_tiles(5, 9, tw, th);
    const std::vector<std::uint32_t> px = make_views(views, tw, th, gradient);
    const LenticularMapping m = lenticular_mapping(c);
    const std::vector<std::uint32_t> gpu_panel = compose(px, views, layout, m);
    const RgbImage cpu = interleave(cpu_quilt(px, views, layout).view(), layout, views, m);
    EXPECT_EQ(gpu_panel.size(), std::size_t(c.screen_width) * std::size_t(c.screen_height));
    int mismatches = 0;
    for (int y = 0; y < cpu.height(); ++y)
      for (int x = 0; x < cpu.width(); ++x)
        for (int ch = 0; ch < 3; ++ch) {
          const std::uint8_t want = metrics::srgb8_encode(cpu.pixel(x, y)[ch]);
          const auto got = std::uint8_t(gpu_panel[std::size_t(y) * std::size_t(cpu.width()) + std::size_t(x)] >> (8 * ch));
          if (want != got && ++mismatches <= 3)
            ADD_FAILURE() << "panel " << x << "," << y << " channel " << ch << ": GPU " << int(got)
                          << ", CPU " << int(want);
        }
    return mismatches;
  }
};

TEST_F(GpuCompositorTest, LenticularEqualsCpuInterleaveOnPortraitPanel) {
  // Distinct colours per view plus ramps inside each tile: the view choice and the bilinear
  // weights both show in every byte.
  EXPECT_EQ(lenticular_mismatches(portrait(true, false, false, false), 48, 42, 56, true), 0);
}

TEST_F(GpuCompositorTest, LenticularEqualsCpuInterleaveOnSixteenInchPanel) {
  EXPECT_EQ(lenticular_mismatches(sixteen(false, false, false, false), 45, 41, 23, true), 0);
}

TEST_F(GpuCompositorTest, LenticularEqualsCpuInterleaveWithEveryFlipFlag) {
  for (int flags = 0; flags < 16; ++flags) {
    SCOPED_TRACE("invView flipImageX flipImageY flipSubp = " + std::to_string(flags & 1) +
                 std::to_string((flags >> 1) & 1) + std::to_string((flags >> 2) & 1) +
                 std::to_string((flags >> 3) & 1));
    EXPECT_EQ(lenticular_mismatches(small(flags & 1, flags & 2, flags & 4, flags & 8), 48, 12, 16,
                                    true),
              0);
  }
}

TEST_F(GpuCompositorTest, AtlasEqualsTheQuiltTheWriterComposes) {
  // A 16-inch-like layout with a spare column and row (tiles keep to the bottom-left), fewer
  // views than cells, and a stereo pair: pixel for pixel, empty cells black.
  for (auto [layout, views] : {std::pair{layout_from_atlas(5, 9, 64, 48), 43},
                               std::pair{layout_from_tiles(2, 1, 20, 16), 2},
                               std::pair{layout_from_tiles(1, 1, 30, 20), 1}}) {
    const std::vector<std::uint32_t> px = make_views(views, layout.tile_width, layout.tile_height, true);
    const std::vector<std::uint32_t> out = compose(px, views, layout, std::nullopt);
    ASSERT_EQ(out.size(), std::size_t(layout.width) * std::size_t(layout.height));
    int mismatches = 0;
    for (int y = 0; y < layout.height; ++y)
      for (int x = 0; x < layout.width; ++x) {
        std::uint32_t want = 0xFF000000u;
        for (int k = 0; k < views; ++k) {
          const TileRect t = layout.tile(k);
          if (x >= t.x && x < t.x + t.width && y >= t.y && y < t.y + t.height)
            want = px[(std::size_t(k) * std::size_t(t.height) + std::size_t(y - t.y)) * std::size_t(t.width) +
                      std::size_t(x - t.x)];
        }
        if (out[std::size_t(y) * std::size_t(layout.width) + std::size_t(x)] != want) ++mismatches;
      }
    EXPECT_EQ(mismatches, 0) << layout.columns << "x" << layout.rows << ", " << views << " views";
  }
}

TEST_F(GpuCompositorTest, OverlayMarksEachPointInEveryViewWithItsOwnProjection) {
  // Two views of 16 x 12, identity matrices but the second shifted by a quarter of the width in
  // NDC (0.5): a point at the origin lands at pixel (8, 6) in view 0 and (12, 6) in view 1.
  const QuiltLayout layout = layout_from_tiles(2, 1, 16, 12);
  const std::vector<float> decoded = decoded_table();
  GpuCompositor comp(device(), layout, 2, std::nullopt,
                     Srgb8Tables{std::span<const float, 256>(decoded.data(), 256), metrics::srgb8_midpoints()});
  glm::mat4 shifted(1.0f);
  shifted[3][0] = 0.5f;
  const std::vector<glm::mat4> matrices{glm::mat4(1.0f), shifted};
  const std::vector<GpuCompositor::OverlayPoint> points{{glm::vec3(0.0f, 0.0f, 0.5f), 0xFF00FF00u},
                                                        {glm::vec3(5.0f, 0.0f, 0.5f), 0xFF0000FFu}};
  comp.set_overlay(points, matrices);  // the second point is off screen in both views
  const std::vector<std::uint32_t> px = make_views(2, 16, 12, false);
  gpu::Buffer input(device(), px.size() * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUse::upload);
  input.write(px.data(), px.size() * 4);
  gpu::CommandRunner runner(device());
  runner.run([&](VkCommandBuffer cmd) {
    comp.record_gather(cmd, input, 0, 2, 16, 12);
    comp.record_compose(cmd);
  });
  const auto out = gpu::download<std::uint32_t>(device(), runner, comp.output(), 32 * 12);
  int marked = 0;
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 32; ++x) {
      const int view = x / 16, tx = x % 16;
      const int cx = view == 0 ? 8 : 12;
      const bool dot = std::abs(tx - cx) <= 1 && std::abs(y - 6) <= 1;
      const std::uint32_t want = dot ? 0xFF00FF00u : px[(std::size_t(view) * 12 + std::size_t(y)) * 16 + std::size_t(tx)];
      EXPECT_EQ(out[std::size_t(y) * 32 + std::size_t(x)], want) << x << "," << y;
      marked += dot;
    }
  EXPECT_EQ(marked, 18);
  comp.set_overlay({}, {});  // off again: the views as they are
  runner.run([&](VkCommandBuffer cmd) {
    comp.record_gather(cmd, input, 0, 2, 16, 12);
    comp.record_compose(cmd);
  });
  const auto plain = gpu::download<std::uint32_t>(device(), runner, comp.output(), 32 * 12);
  EXPECT_EQ(plain[6 * 32 + 8], px[6 * 16 + 8]);
  EXPECT_THROW(comp.set_overlay(points, std::span<const glm::mat4>(matrices.data(), 1)), std::invalid_argument);
}

// Every character of the font, small letters, a character the font lacks, and a status line.
const std::vector<std::string> kText{" 0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ.,:/-+()%=?_",
                                     "abc xyz #&", "PROBES 12.3  RASTER 45.6  PRESENT 0.8 MS"};
const std::vector<std::string> kTextRead{" 0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ.,:/-+()%=?_",
                                         "ABC XYZ ??", "PROBES 12.3  RASTER 45.6  PRESENT 0.8 MS"};

TEST_F(GpuCompositorTest, FontGlyphsAreDistinctAndLookedUpAsDocumented) {
  const auto glyphs = font_glyphs();
  ASSERT_EQ(glyphs.size(), font_characters().size());
  for (std::size_t a = 0; a < glyphs.size(); ++a)
    for (std::size_t b = a + 1; b < glyphs.size(); ++b)
      EXPECT_NE(glyphs[a], glyphs[b]) << font_characters()[a] << " and " << font_characters()[b];
  EXPECT_EQ(glyph_index(' '), 0u);
  EXPECT_EQ(glyph_index('q'), glyph_index('Q'));
  EXPECT_EQ(glyph_index('#'), glyph_index('?'));
  // '1': a centred stem with a flag and a foot.
  EXPECT_EQ(glyphs[glyph_index('1')], (Glyph{0b00100, 0b01100, 0b00100, 0b00100, 0b00100, 0b00100, 0b01110}));
  EXPECT_EQ(status_box_width(1), 339);
  EXPECT_EQ(status_box_height(2, 3), 3 * 20);
}

TEST_F(GpuCompositorTest, StatusTextOnTheAtlasEqualsTheCpuDrawingOfTheFont) {
  // A single view wide enough for the box at scale 1, and at scale 2 cut by the image's edges;
  // then the text off again. The box covers the top-left corner; the rest is the view.
  const QuiltLayout layout = layout_from_tiles(1, 1, 360, 40);
  const std::vector<std::uint32_t> px = make_views(1, 360, 40, true);
  for (const int scale : {1, 2}) {
    SCOPED_TRACE("scale " + std::to_string(scale));
    const std::vector<std::uint32_t> out =
        compose(px, 1, layout, std::nullopt, [&](GpuCompositor& c) { c.set_status(kText, scale); }, 2);
    std::vector<std::uint32_t> want = px;
    test::draw_status(want, 0, 360, 40, kText, scale);
    int mismatches = 0;
    for (std::size_t i = 0; i < want.size(); ++i) mismatches += out[i] != want[i];
    EXPECT_EQ(mismatches, 0);
    if (scale == 1) {
      EXPECT_EQ(test::read_status([&](int x, int y) { return out[std::size_t(y) * 360 + std::size_t(x)]; }, 3, 1),
                kTextRead);
      EXPECT_EQ(out[std::size_t(38) * 360 + 200], px[std::size_t(38) * 360 + 200]);  // below the box
    }
  }
  const std::vector<std::uint32_t> off = compose(px, 1, layout, std::nullopt, [&](GpuCompositor& c) {
    c.set_status(kText, 1);
    c.set_status({}, 1);
  });
  EXPECT_EQ(off, px);
  const std::vector<float> decoded = decoded_table();
  GpuCompositor comp(device(), layout, 1, std::nullopt,
                     Srgb8Tables{std::span<const float, 256>(decoded.data(), 256), metrics::srgb8_midpoints()});
  EXPECT_THROW(comp.set_status(kText, 0), std::invalid_argument);
}

TEST_F(GpuCompositorTest, StatusTextOnAPanelIsInEveryViewBeforeTheInterleave) {
  // The text drawn into each view (cut at the views' 60 x 80), then the CPU interleave of those
  // views equals the GPU panel byte for byte; composing again on the same views (a held frame)
  // changes nothing.
  const Calibration c = small(true, false, false, false);
  const QuiltLayout layout = layout_from_tiles(8, 6, 60, 80);
  std::vector<std::uint32_t> px = make_views(48, 60, 80, true);
  const LenticularMapping m = lenticular_mapping(c);
  const std::vector<std::string> lines{"PROBES 1.2", "48 VIEWS"};
  const std::vector<std::uint32_t> panel =
      compose(px, 48, layout, m, [&](GpuCompositor& g) { g.set_status(lines, 1); }, 2);
  for (int k = 0; k < 48; ++k) test::draw_status(px, std::size_t(k) * 60 * 80, 60, 80, lines, 1);
  const RgbImage cpu = interleave(cpu_quilt(px, 48, layout).view(), layout, 48, m);
  ASSERT_EQ(panel.size(), std::size_t(cpu.width()) * std::size_t(cpu.height()));
  int mismatches = 0, text_changed = 0;
  const std::vector<std::uint32_t> plain = compose(make_views(48, 60, 80, true), 48, layout, m);
  for (int y = 0; y < cpu.height(); ++y)
    for (int x = 0; x < cpu.width(); ++x) {
      const std::size_t i = std::size_t(y) * std::size_t(cpu.width()) + std::size_t(x);
      text_changed += panel[i] != plain[i];
      for (int ch = 0; ch < 3; ++ch)
        mismatches += metrics::srgb8_encode(cpu.pixel(x, y)[ch]) != std::uint8_t(panel[i] >> (8 * ch));
    }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(text_changed, 1000);  // the text is really there: a panel region the size of the box
}

TEST_F(GpuCompositorTest, BadGatherIsRefused) {
  const std::vector<float> decoded = decoded_table();
  GpuCompositor comp(device(), layout_from_tiles(2, 1, 8, 8), 2, std::nullopt,
                     Srgb8Tables{std::span<const float, 256>(decoded.data(), 256), metrics::srgb8_midpoints()});
  gpu::Buffer b(device(), 8 * 8 * 4 * 2, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryUse::upload);
  gpu::CommandRunner runner(device());
  EXPECT_THROW(runner.run([&](VkCommandBuffer cmd) { comp.record_gather(cmd, b, 1, 2, 8, 8); }),
               std::invalid_argument);
  EXPECT_THROW(runner.run([&](VkCommandBuffer cmd) { comp.record_gather(cmd, b, 0, 2, 8, 9); }),
               std::invalid_argument);
}

}  // namespace
}  // namespace ddish::display
