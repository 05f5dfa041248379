#include "imagery_cli.hpp"

#include "tellus/core/cache_folder.hpp"

#include <cstdlib>

#include <unistd.h>

#include "cli_numbers.hpp"

namespace tellus::cli {

void addImageryOptions(CLI::App* app, ImageryCliOptions& o) {
  app->add_option("--imagery", o.files,
                  "Georeferenced RGB(A) rasters (GeoTIFF, JPEG or PNG with a world file; any CRS) "
                  "draped over the terrain (flat, globe, or the tops of a georeferenced .tstack), "
                  "later ones on top; warped onto the terrain's grid once and cached beside it "
                  "(INPUT.imagery/)");
  app->add_option("--imagery-budget", o.budgetMiB,
                  "GPU memory for imagery pages, MiB (default 96)")
      ->check(numberIn(1.0, 65536.0));
  app->add_option("--imagery-uploads", o.uploadsPerFrame,
                  "Imagery pages (256^2 texels each) transferred a frame at most (default 8)")
      ->check(integerIn(1, 4096));
}

std::filesystem::path imageryCacheFolder(const std::string& input) {
  return derivedCacheFolder(input, ".imagery", "imagery");
}

Result<std::unique_ptr<ImageryTextures>> makeImagery(const ImageryCliOptions& o, const HeightGrid* flatGrid,
                                                     const std::string& input) {
  if (!o.any()) return std::unique_ptr<ImageryTextures>();
  const std::vector<std::filesystem::path> sources(o.files.begin(), o.files.end());
  Result<std::vector<ImageryLayer>> layers =
      flatGrid ? imageryLayersOnGrid(sources, flatGrid->georef, flatGrid->width, flatGrid->height,
                                     flatGrid->spacingXM, flatGrid->spacingYM, imageryCacheFolder(input))
               : imageryLayersOnGlobe(sources, imageryCacheFolder(input));
  if (!layers) return layers.error();
  ImageryBudget budget;
  budget.memoryBytes = std::uint64_t(o.budgetMiB * 1024.0 * 1024.0);
  budget.uploadsPerFrame = o.uploadsPerFrame;
  return ImageryTextures::create(std::move(layers.value()), budget,
                                 flatGrid ? ImageryFrame::FlatWorld : ImageryFrame::LonLat);
}

}  // namespace tellus::cli
