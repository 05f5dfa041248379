#include "tellus/lod/clipmaps/clipmap_update.hpp"

namespace tellus::clipmaps {

ClipmapUpdate buildClipmapUpdate(const ClipmapShape& shape, const std::vector<glm::ivec2>* from,
                                 glm::dvec2 viewer, const LevelSampler& sampler) {
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
        rect.texels.reserve(std::size_t(rect.size.x) * std::size_t(rect.size.y));
        for (int y = piece.samples.min.y; y < piece.samples.max.y; ++y) {
          for (int x = piece.samples.min.x; x < piece.samples.max.x; ++x) {
            rect.texels.push_back(texelHeights(sampler, shape, level, {x, y}));
          }
        }
        update.samples += rect.texels.size();
        update.rects.push_back(std::move(rect));
      }
    }
  }
  return update;
}

}  // namespace tellus::clipmaps
