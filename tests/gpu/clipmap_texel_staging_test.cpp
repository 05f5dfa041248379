// The clipmaps' staged texel copy (render/clipmaps/clipmap_texel_staging.hpp): a worker writes an
// update's rectangles into a mapped slot, and the GPU's copy pass stores them into the height
// texture array exactly where a CPU placement of the same rectangles puts them, on every layer,
// at the texture's edges, around empty rectangles; slots are handed out without waiting and come
// back only once the GPU has finished copying from them; an update too large is refused.
#include <algorithm>
#include <random>
#include <set>
#include <vector>

#include <glm/vector_relational.hpp>
#include <gtest/gtest.h>

#include "support/gl_test.hpp"
#include "tellus/gl/gpu_wait.hpp"
#include "tellus/gl/texture.hpp"
#include "tellus/render/clipmaps/clipmap_texel_staging.hpp"

namespace tellus {
namespace {

class ClipmapTexelStagingTest : public test::GlTest {
 protected:
  static clipmaps::ClipmapShape shape() {
    clipmaps::ClipmapShape s;
    s.n = 63;
    s.m = 16;
    s.textureSize = 64;
    s.levels = 3;
    return s;
  }
};

constexpr glm::vec2 kUntouched(-7.0f, -9.0f);

// The layers (row-major texels, layer after layer) once `rects` are placed on `before`.
std::vector<glm::vec2> placeOnCpu(std::vector<glm::vec2> texels, const std::vector<clipmaps::TexelRect>& rects,
                                  int size) {
  for (const clipmaps::TexelRect& rect : rects) {
    for (int y = 0; y < rect.size.y; ++y) {
      for (int x = 0; x < rect.size.x; ++x) {
        const std::size_t at = (std::size_t(rect.level) * std::size_t(size) + std::size_t(rect.texel.y + y)) *
                                   std::size_t(size) + std::size_t(rect.texel.x + x);
        texels[at] = rect.texels[std::size_t(y * rect.size.x + x)];
      }
    }
  }
  return texels;
}

std::vector<glm::vec2> readLayers(const gl::Texture& texture, int size, int layers) {
  std::vector<glm::vec2> texels(std::size_t(size) * std::size_t(size) * std::size_t(layers));
  gl::readTextureSubImage(texture.id(), 0, 0, 0, 0, size, size, layers, GL_RG, GL_FLOAT,
                          texels.size() * sizeof(glm::vec2), texels.data());
  return texels;
}

clipmaps::TexelRect rectWithValues(int level, glm::ivec2 texel, glm::ivec2 size, float tag) {
  clipmaps::TexelRect rect;
  rect.level = level;
  rect.texel = texel;
  rect.size = size;
  for (int y = 0; y < size.y; ++y) {
    for (int x = 0; x < size.x; ++x) rect.texels.emplace_back(tag + float(y * size.x + x), float(level) - tag);
  }
  return rect;
}

TEST_F(ClipmapTexelStagingTest, TheGpuCopyPlacesEveryRectangleLikeTheCpu) {
  const clipmaps::ClipmapShape s = shape();
  Result<std::unique_ptr<ClipmapTexelStaging>> created = ClipmapTexelStaging::create(s);
  ASSERT_TRUE(created) << created.error().message;
  ClipmapTexelStaging& staging = *created.value();
  gl::Texture heights = gl::Texture::create2DArray(GL_RG32F, s.textureSize, s.textureSize, s.levels);
  glClearTexImage(heights.id(), 0, GL_RG, GL_FLOAT, &kUntouched);
  std::vector<glm::vec2> expected(std::size_t(s.textureSize * s.textureSize * s.levels), kUntouched);

  std::mt19937 random(11);
  for (int round = 0; round < 4; ++round) {
    clipmaps::ClipmapUpdate update;
    // An L at the texture's far corner, cut where it wraps, an empty rectangle, random ones.
    update.rects.push_back(rectWithValues(round % 3, {60, 0}, {4, 64}, 1000.0f * float(round)));
    update.rects.push_back(rectWithValues(round % 3, {0, 61}, {60, 3}, 1000.0f * float(round) + 300.0f));
    update.rects.push_back(rectWithValues(2, {5, 5}, {0, 9}, 0.0f));
    // Random ones that overlap none before them (an update's rectangles never overlap).
    for (int k = 0; k < 40 && update.rects.size() < 15; ++k) {
      std::uniform_int_distribution<int> side(1, 40), level(0, 2);
      const glm::ivec2 size(side(random), side(random));
      std::uniform_int_distribution<int> x(0, s.textureSize - size.x), y(0, s.textureSize - size.y);
      clipmaps::TexelRect rect = rectWithValues(level(random), {x(random), y(random)}, size, float(k * 100000 + round));
      const auto overlaps = [&](const clipmaps::TexelRect& o) {
        return o.level == rect.level && glm::all(glm::lessThan(o.texel, rect.texel + rect.size)) &&
               glm::all(glm::lessThan(rect.texel, o.texel + o.size));
      };
      if (std::none_of(update.rects.begin(), update.rects.end(), overlaps)) update.rects.push_back(std::move(rect));
    }
    ASSERT_GT(update.rects.size(), 8u);
    for (const clipmaps::TexelRect& rect : update.rects) update.samples += rect.texels.size();
    expected = placeOnCpu(expected, update.rects, s.textureSize);

    const int slot = staging.acquire();
    ASSERT_GE(slot, 0);
    ASSERT_TRUE(staging.write(slot, update));
    for (const clipmaps::TexelRect& rect : update.rects) EXPECT_TRUE(rect.texels.empty());  // moved to the slot
    staging.copy(slot, heights);
    const std::vector<glm::vec2> gpu = readLayers(heights, s.textureSize, s.levels);
    for (std::size_t k = 0; k < expected.size(); ++k) {
      ASSERT_EQ(gpu[k], expected[k]) << "round " << round << ", layer " << k / (64 * 64) << ", texel "
                                     << k % 64 << "," << (k / 64) % 64;
    }
  }
}

TEST_F(ClipmapTexelStagingTest, SlotsAreLentWithoutWaitingAndComeBackAfterTheirCopy) {
  const clipmaps::ClipmapShape s = shape();
  Result<std::unique_ptr<ClipmapTexelStaging>> created = ClipmapTexelStaging::create(s);
  ASSERT_TRUE(created) << created.error().message;
  ClipmapTexelStaging& staging = *created.value();
  gl::Texture heights = gl::Texture::create2DArray(GL_RG32F, s.textureSize, s.textureSize, s.levels);

  std::vector<int> held;
  for (int k = 0; k < ClipmapTexelStaging::kSlots; ++k) held.push_back(staging.acquire());
  EXPECT_EQ(std::set<int>(held.begin(), held.end()).size(), std::size_t(ClipmapTexelStaging::kSlots));
  EXPECT_EQ(staging.acquire(), -1);  // all held: the caller uploads directly
  staging.release(held[0]);
  EXPECT_EQ(staging.acquire(), held[0]);

  clipmaps::ClipmapUpdate update;
  update.rects.push_back(rectWithValues(1, {0, 0}, {64, 64}, 1.0f));
  update.samples = update.rects[0].texels.size();
  ASSERT_TRUE(staging.write(held[1], update));
  staging.copy(held[1], heights);
  glFinish();  // the copy has run: its slot is free again
  EXPECT_EQ(staging.acquire(), held[1]);
}

TEST_F(ClipmapTexelStagingTest, AnUpdateTooLargeForASlotIsRefusedAndLeftWhole) {
  const clipmaps::ClipmapShape s = shape();
  Result<std::unique_ptr<ClipmapTexelStaging>> created = ClipmapTexelStaging::create(s);
  ASSERT_TRUE(created) << created.error().message;
  ClipmapTexelStaging& staging = *created.value();
  const int slot = staging.acquire();
  ASSERT_GE(slot, 0);

  clipmaps::ClipmapUpdate tooMany;  // more rectangles than a slot's table holds
  for (int k = 0; k < 1000; ++k) tooMany.rects.push_back(rectWithValues(0, {k % 64, 0}, {1, 1}, float(k)));
  tooMany.samples = 1000;
  EXPECT_FALSE(staging.write(slot, tooMany));
  EXPECT_EQ(tooMany.rects[999].texels.size(), 1u);  // untouched: the caller uploads them

  clipmaps::ClipmapUpdate tooBig;  // more texels than every level's whole layer
  for (int level = 0; level < 4; ++level) tooBig.rects.push_back(rectWithValues(0, {0, 0}, {64, 64}, 0.0f));
  tooBig.samples = 4 * 64 * 64;
  EXPECT_FALSE(staging.write(slot, tooBig));
  EXPECT_EQ(tooBig.rects[0].texels.size(), std::size_t(64 * 64));
}

}  // namespace
}  // namespace tellus
