// Displacement maps: loading (PNG 8/16-bit, channels, EXR, procedural), the mip chain and
// the conservative range of the map over texture regions (bound/displaced_map.h).
#include "adapters/image_channel.h"
#include "adapters/image_displacement.h"
#include "adapters/image_png.h"
#include "osd_cull/bound/displaced_map.h"
#include "osd_cull/error.h"
#include "osd_cull/scene/procedural_displacement.h"
#include "support/temp_dir.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <vector>

namespace {

using osd_cull::Error;
using osd_cull::bound::DisplacementMap;
using osd_cull::bound::UvRegion;

std::vector<float> randomTexels(uint32_t w, uint32_t h, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<float> t(static_cast<size_t>(w) * h);
  for (float& v : t) v = u(rng);
  return t;
}

// Every filtered sample the draw can take in a region (any lod up to maxLod) lies in the
// range rangeOver() gives, including regions that wrap around the map's edges.
void expectRangeHoldsSamples(const DisplacementMap& map, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(-1.3, 2.1), size(0.0, 0.2), unit(0.0, 1.0);
  for (int r = 0; r < 200; ++r) {
    UvRegion region;
    region.lo = {pos(rng), pos(rng)};
    region.hi = region.lo + glm::dvec2(size(rng), size(rng));
    const auto range = map.rangeOver(region);
    for (int s = 0; s < 50; ++s) {
      const glm::dvec2 st = region.lo + (region.hi - region.lo) * glm::dvec2(unit(rng), unit(rng));
      const double lod = unit(rng) * map.maxLod();
      const double v = map.sample(st, lod);
      ASSERT_GE(v, range.lo) << "region " << r << " sample " << s;
      ASSERT_LE(v, range.hi) << "region " << r << " sample " << s;
    }
  }
}

TEST(DisplacementMap, RangeOverRegionHoldsEverySampleAtLevelZero) {
  DisplacementMap map("random", 37, 23, randomTexels(37, 23, 1), 1.0, 0.5);
  EXPECT_EQ(map.levelCount(), 1u);  // not a power of two: no mips
  expectRangeHoldsSamples(map, 2);
}

TEST(DisplacementMap, RangeOverRegionHoldsEverySampleUpToMaxLod) {
  DisplacementMap map("random", 64, 32, randomTexels(64, 32, 3), 1.0, 0.5, 3);
  EXPECT_EQ(map.levelCount(), 7u);
  EXPECT_EQ(map.levelWidth(3), 8u);
  EXPECT_EQ(map.levelHeight(6), 1u);
  expectRangeHoldsSamples(map, 4);
}

TEST(DisplacementMap, RangeOfASmallRegionIsLocal) {
  // A single spike: regions far from it do not see it, regions over it do.
  std::vector<float> texels(64 * 64, 0.25f);
  texels[40 * 64 + 10] = 1.0f;
  DisplacementMap map("spike", 64, 64, texels, 2.0, 0.5);
  const auto far = map.rangeOver({{0.5, 0.1}, {0.6, 0.2}});
  EXPECT_EQ(far.hi, 0.25);
  const auto over = map.rangeOver({{10.5 / 64, 40.5 / 64}, {10.5 / 64, 40.5 / 64}});
  EXPECT_EQ(over.hi, 1.0);
  // Displacement: 2 * (v - 0.5), widened to contain 0.
  const auto d = map.displacementOver({{0.5, 0.1}, {0.6, 0.2}});
  EXPECT_NEAR(d.dmin, -0.5, 1e-4);
  EXPECT_LE(d.dmin, -0.5);
  EXPECT_GE(d.dmax, 0.0);
  EXPECT_LT(d.dmax, 1e-4);
}

TEST(DisplacementMap, MipLevelsAreBoxAverages) {
  std::vector<float> texels = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
  DisplacementMap map("ramp", 4, 4, texels, 1.0, 0.0, 2);
  ASSERT_EQ(map.levelCount(), 3u);
  EXPECT_FLOAT_EQ(map.level(1)[0], (0 + 1 + 4 + 5) / 4.0f);
  EXPECT_FLOAT_EQ(map.level(2)[0], 7.5f);
}

TEST(DisplacementMap, BadInputIsNamed) {
  EXPECT_THROW(DisplacementMap("x", 0, 4, {}, 1.0, 0.5), Error);
  EXPECT_THROW(DisplacementMap("x", 2, 2, {0, 1, 2}, 1.0, 0.5), Error);
  EXPECT_THROW(DisplacementMap("x", 2, 2, {0, 1, 2, NAN}, 1.0, 0.5), Error);
  EXPECT_THROW(DisplacementMap("x", 2, 2, {0, 1, 2, 3}, INFINITY, 0.5), Error);
  try {
    DisplacementMap("odd", 3, 3, std::vector<float>(9, 0.0f), 1.0, 0.5, 1);
    FAIL() << "a mip level on a non-power-of-two map was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("powers of two"), std::string::npos) << e.what();
  }
}

// A one-channel (gray) PNG of `width` x `height` samples, top row first, written into `dir`.
std::filesystem::path writeGrayPng(const osd_cull::test::TempDir& dir, const char* name,
                                   uint32_t width, uint32_t height, int bitDepth,
                                   const std::vector<uint16_t>& samples) {
  osd_cull::adapters::PngImage image;
  image.width = width;
  image.height = height;
  image.channels = 1;
  image.bitDepth = bitDepth;
  if (bitDepth == 16)
    image.samples16 = samples;
  else
    image.samples8.assign(samples.begin(), samples.end());
  const auto path = dir.path() / name;
  osd_cull::adapters::writePng(path, image);
  return path;
}

TEST(DisplacementImages, Png16BitGrayIsNormalisedAndFlipped) {
  osd_cull::test::TempDir dir("osd_cull_disp_");
  const auto path = writeGrayPng(dir, "gray16.png", 2, 2, 16, {0, 65535, 32768, 1000});
  const auto ch = osd_cull::adapters::detail::readPngChannel(path, 'r');
  ASSERT_EQ(ch.width, 2u);
  EXPECT_EQ(ch.bitDepth, 16);
  EXPECT_TRUE(ch.normalized);
  // Row 0 of the channel is the bottom row of the picture (t = 0).
  EXPECT_FLOAT_EQ(ch.texels[0], 32768.0f / 65535.0f);
  EXPECT_FLOAT_EQ(ch.texels[3], 1.0f);
  EXPECT_THROW(osd_cull::adapters::detail::readPngChannel(path, 'a'), Error);
}

TEST(DisplacementImages, OneChannelPngRefusesGreenAndBlueAsItRefusesAlpha) {
  osd_cull::test::TempDir dir("osd_cull_disp_");
  const auto path = writeGrayPng(dir, "gray8.png", 2, 1, 8, {0, 255});
  EXPECT_EQ(osd_cull::adapters::detail::readPngChannel(path, 'r').texels[1], 1.0f);
  for (const char channel : {'g', 'b', 'a'}) {
    try {
      osd_cull::adapters::detail::readPngChannel(path, channel);
      ADD_FAILURE() << "accepted channel " << channel << " of a gray PNG";
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("gray8.png"), std::string::npos) << what;
      EXPECT_NE(what.find(channel == 'a' ? "has no alpha channel"
                                         : std::string("has no channel '") + channel + "'"),
                std::string::npos)
          << what;
    }
  }
}

TEST(DisplacementImages, PngRgbaChannelIsChosen) {
  osd_cull::test::TempDir dir("osd_cull_disp_");
  osd_cull::adapters::PngImage image;
  image.width = 1;
  image.height = 1;
  image.channels = 4;
  image.samples8 = {10, 20, 30, 255};
  const auto path = dir.path() / "rgba.png";
  osd_cull::adapters::writePng(path, image);
  osd_cull::adapters::DisplacementOptions options;
  options.source = path.string();
  options.channel = 'b';
  options.scale = 2.0;
  const auto map = osd_cull::adapters::loadDisplacementMap(options);
  EXPECT_FLOAT_EQ(map.level(0)[0], 30.0f / 255.0f);
  EXPECT_EQ(map.midlevel(), 0.5);  // unsigned image default
  EXPECT_NEAR(map.displacement(map.level(0)[0]), 2.0 * (30.0 / 255.0 - 0.5), 1e-7);
  options.channel = 'a';
  EXPECT_FLOAT_EQ(osd_cull::adapters::loadDisplacementMap(options).level(0)[0], 1.0f);
}

TEST(DisplacementImages, ExrFloatChannelRoundTrips) {
  osd_cull::test::TempDir dir("osd_cull_disp_");
  osd_cull::adapters::detail::ImageChannel image;
  image.width = 3;
  image.height = 2;
  image.texels = {-1.5f, 0.0f, 2.25f, 7.0f, -0.125f, 1e-3f};
  const auto path = dir.path() / "height.exr";
  osd_cull::adapters::detail::writeExrChannel(path, image, "Y");
  osd_cull::adapters::DisplacementOptions options;
  options.source = path.string();
  const auto map = osd_cull::adapters::loadDisplacementMap(options);  // 'r' falls back to Y
  EXPECT_EQ(map.midlevel(), 0.0);                                     // float image default
  ASSERT_EQ(map.width(), 3u);
  for (size_t i = 0; i < image.texels.size(); ++i) EXPECT_EQ(map.level(0)[i], image.texels[i]);
  options.channel = 'a';
  EXPECT_THROW(osd_cull::adapters::loadDisplacementMap(options), Error);
}

TEST(DisplacementImages, BadFilesAndOptionsAreNamed) {
  osd_cull::test::TempDir dir("osd_cull_disp_");
  osd_cull::adapters::DisplacementOptions options;
  options.source = (dir.path() / "missing.png").string();
  EXPECT_THROW(osd_cull::adapters::loadDisplacementMap(options), Error);
  options.source = dir.write("fake.png", "not a png at all").string();
  try {
    osd_cull::adapters::loadDisplacementMap(options);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("fake.png"), std::string::npos) << e.what();
  }
  options.source = dir.write("fake.exr", "not an exr").string();
  EXPECT_THROW(osd_cull::adapters::loadDisplacementMap(options), Error);
  options.source = dir.write("map.tga", "x").string();
  EXPECT_THROW(osd_cull::adapters::loadDisplacementMap(options), Error);
  options.source = "";
  EXPECT_THROW(osd_cull::adapters::loadDisplacementMap(options), Error);
  EXPECT_THROW(osd_cull::adapters::parseDisplacementChannel("x"), Error);
  EXPECT_EQ(osd_cull::adapters::parseDisplacementChannel("a"), 'a');
}

TEST(ProceduralDisplacement, IsDeterministicNormalisedAndSeamless) {
  const auto a = osd_cull::scene::proceduralDisplacementTexels(64, 3, 7);
  EXPECT_EQ(a, osd_cull::scene::proceduralDisplacementTexels(64, 3, 7));
  EXPECT_NE(a, osd_cull::scene::proceduralDisplacementTexels(64, 3, 8));
  EXPECT_EQ(*std::min_element(a.begin(), a.end()), 0.0f);
  EXPECT_EQ(*std::max_element(a.begin(), a.end()), 1.0f);
  // Periodic: the jump across the wrap is no larger than the largest jump inside.
  double inside = 0.0, across = 0.0;
  for (uint32_t y = 0; y < 64; ++y) {
    for (uint32_t x = 0; x + 1 < 64; ++x)
      inside = std::max(inside, double(std::abs(a[y * 64 + x + 1] - a[y * 64 + x])));
    across = std::max(across, double(std::abs(a[y * 64] - a[y * 64 + 63])));
  }
  EXPECT_LE(across, inside);
  EXPECT_THROW(osd_cull::scene::proceduralDisplacementTexels(100), Error);
  EXPECT_THROW(osd_cull::scene::proceduralDisplacementTexels(16, 4), Error);
}

}  // namespace
