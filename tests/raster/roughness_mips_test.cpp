// Metallic-roughness mip chains (raster/roughness_mips.h): roughness (G) is a power mean of the
// texels a level covers, the other channels a linear mean, and the chain has the sizes Vulkan's
// mip levels have.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "../gpu/gpu_test.h"
#include "gpu/commands.h"
#include "raster/material_textures.h"
#include "raster/roughness_mips.h"

namespace ddish::raster::test {
namespace {

// A 2 x 1 texture: roughness 0 and 1 (G), metallic 0 and 1 (B), occlusion 64 and 192 (R).
scene::Texture two_texels() {
  return scene::Texture{"two", 2, 1, {64, 0, 0, 255, 192, 255, 255, 255}};
}

TEST(RoughnessMips, TwoTexelsTakeThePowerMean) {
  const scene::Texture tex = two_texels();
  // p = 0.5: ((0^0.5 + 1^0.5) / 2)^2 = 0.25 -> 63.75 -> 64; p = 2: sqrt(0.5) = 0.7071 -> 180.3
  // -> 180; p = 1: 0.5 -> 127.5 -> 128 (lround rounds half away from zero).
  for (const auto& [power, expected] : {std::pair{0.5f, 64}, std::pair{2.0f, 180}, std::pair{1.0f, 128}}) {
    const std::vector<MipLevel> chain = roughness_mip_chain(tex, power);
    ASSERT_EQ(chain.size(), 2u);
    EXPECT_EQ(chain[0].rgba8, tex.rgba8);  // level 0 unchanged
    ASSERT_EQ(chain[1].width, 1u);
    ASSERT_EQ(chain[1].height, 1u);
    EXPECT_EQ(chain[1].rgba8[1], expected) << "power " << power;
    EXPECT_EQ(chain[1].rgba8[0], 128);  // occlusion: linear mean (64 + 192) / 2
    EXPECT_EQ(chain[1].rgba8[2], 128);  // metallic: linear mean 127.5, rounded
    EXPECT_EQ(chain[1].rgba8[3], 255);
  }
}

TEST(RoughnessMips, EachLevelIsThePowerMeanOfItsWholeFootprint) {
  // 4 x 1, roughness 0, 0, 0, 1 (G), p = 0.5: level 1 is (0, (1/2)^2 = 0.25 -> 64), level 2 the
  // power mean of all four texels, (1/4)^2 = 0.0625 -> 15.9 -> 16 (the linear mean would be 64).
  const scene::Texture a{"a", 4, 1, {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 255, 0, 0}};
  const std::vector<MipLevel> chain = roughness_mip_chain(a, 0.5f);
  ASSERT_EQ(chain.size(), 3u);
  EXPECT_EQ(chain[1].width, 2u);
  EXPECT_EQ(chain[1].rgba8[1], 0);
  EXPECT_EQ(chain[1].rgba8[5], 64);  // (1/2)^2 = 0.25
  EXPECT_EQ(chain[2].width, 1u);
  EXPECT_EQ(chain[2].rgba8[1], 16);  // (1/4)^2 = 0.0625 -> 15.94
}

TEST(RoughnessMips, ChainSizesFollowVulkanMipLevels) {
  // 5 x 3: 5x3, 2x1, 1x1 (each side halved, rounded down, at least 1): bit_width(5) = 3 levels.
  scene::Texture t{"odd", 5, 3, std::vector<std::uint8_t>(5 * 3 * 4, 100)};
  const std::vector<MipLevel> chain = roughness_mip_chain(t, 0.5f);
  ASSERT_EQ(chain.size(), 3u);
  EXPECT_EQ(chain[1].width, 2u);
  EXPECT_EQ(chain[1].height, 1u);
  EXPECT_EQ(chain[2].width, 1u);
  EXPECT_EQ(chain[2].height, 1u);
  for (const MipLevel& level : chain)  // a constant texture stays constant in every space
    for (std::uint8_t v : level.rgba8) EXPECT_EQ(v, 100);
}

TEST(RoughnessMips, BadInputIsRejected) {
  EXPECT_THROW(roughness_mip_chain(two_texels(), 0.0f), std::invalid_argument);
  scene::Texture short_data{"short", 2, 2, {1, 2, 3}};
  EXPECT_THROW(roughness_mip_chain(short_data, 0.5f), std::invalid_argument);
}

class RoughnessMipsUpload : public gpu::test::GpuTest {};

TEST_F(RoughnessMipsUpload, ChainUploadsAndAMalformedOneIsRejected) {
  // Under the validation layer (on in tests): the chain's copies and barriers are clean.
  gpu::CommandRunner runner(device());
  scene::Texture t{"odd", 5, 3, std::vector<std::uint8_t>(5 * 3 * 4, 100)};
  std::vector<MipLevel> chain = roughness_mip_chain(t, kRoughnessMipPower);
  const gpu::Image image = MaterialTextures::upload_mip_chain(device(), runner, chain, VK_FORMAT_R8G8B8A8_UNORM);
  EXPECT_NE(image.handle(), VK_NULL_HANDLE);
  chain[1].width = 3;  // not half of 5
  EXPECT_THROW(MaterialTextures::upload_mip_chain(device(), runner, chain, VK_FORMAT_R8G8B8A8_UNORM),
               std::invalid_argument);
  EXPECT_THROW(MaterialTextures::upload_mip_chain(device(), runner, {}, VK_FORMAT_R8G8B8A8_UNORM),
               std::invalid_argument);
}

}  // namespace
}  // namespace ddish::raster::test
