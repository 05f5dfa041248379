#include "tellus/lod/clipmaps/clipmap_update.hpp"

namespace tellus::clipmaps {
namespace {

// A level's filtered heights over a rectangle, read back by sample.
struct Block {
  SampleRect rect;
  std::vector<float> heights;
  float at(glm::ivec2 s) const {
    const glm::ivec2 local = s - rect.min;
    return heights[std::size_t(local.y) * std::size_t(rect.max.x - rect.min.x) + std::size_t(local.x)];
  }
};

// texelHeights() over the samples `rect` of `level`: the level's own heights and those of the
// coarser level that coarserSurfaceHeight() reads.
std::vector<glm::vec2> texelsOf(const ClipmapShape& shape, int level, const SampleRect& rect,
                                const LevelSampler& stored, const LevelFilter& filter) {
  Block own{rect, filteredBlock(stored, filter, level, rect)};
  Block coarser;
  if (level + 1 < shape.levels) {
    coarser.rect = {halfFloor(rect.min - 1), halfFloor(rect.max) + 1};
    coarser.heights = filteredBlock(stored, filter, level + 1, coarser.rect);
  }
  const LevelSampler fromBlocks = [&](int l, glm::ivec2 s) { return l == level ? own.at(s) : coarser.at(s); };
  std::vector<glm::vec2> texels;
  texels.reserve(std::size_t(rect.max.x - rect.min.x) * std::size_t(rect.max.y - rect.min.y));
  for (int y = rect.min.y; y < rect.max.y; ++y) {
    for (int x = rect.min.x; x < rect.max.x; ++x) texels.push_back(texelHeights(fromBlocks, shape, level, {x, y}));
  }
  return texels;
}

}  // namespace

ClipmapUpdate buildClipmapUpdate(const ClipmapShape& shape, const std::vector<glm::ivec2>* from,
                                 glm::dvec2 viewer, const LevelSampler& stored, const LevelFilter& filter) {
  ClipmapUpdate update;
  update.viewer = viewer;
  update.origins = placeLevels(shape, viewer);
  for (int level = 0; level < shape.levels; ++level) {
    const glm::ivec2 to = update.origins[std::size_t(level)];
    const std::vector<SampleRect> regions =
        from ? exposedRegions(shape, (*from)[std::size_t(level)], to)
             : std::vector<SampleRect>{SampleRect{to, to + shape.n}};
    for (const SampleRect& region : regions) {
      for (const ToroidalPiece& piece : wrapToroidally(region, shape.textureSize)) {
        TexelRect rect;
        rect.level = level;
        rect.texel = piece.texel;
        rect.size = piece.samples.max - piece.samples.min;
        rect.texels = texelsOf(shape, level, piece.samples, stored, filter);
        update.samples += rect.texels.size();
        update.rects.push_back(std::move(rect));
      }
    }
  }
  return update;
}

}  // namespace tellus::clipmaps
