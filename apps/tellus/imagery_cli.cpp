#include "imagery_cli.hpp"

#include <cstdlib>

#include <unistd.h>

#include "cli_numbers.hpp"

namespace tellus::cli {

void addImageryOptions(CLI::App* app, ImageryCliOptions& o) {
  app->add_option("--imagery", o.files,
                  "Georeferenced RGB(A) rasters (GeoTIFF, JPEG or PNG with a world file; any CRS) "
                  "draped over the flat renderers, later ones on top; warped onto the terrain's "
                  "grid once and cached beside it (INPUT.imagery/)");
  app->add_option("--imagery-budget", o.budgetMiB,
                  "GPU memory for imagery pages, MiB (default 96)")
      ->check(numberIn(1.0, 65536.0));
  app->add_option("--imagery-uploads", o.uploadsPerFrame,
                  "Imagery pages (256^2 texels each) transferred a frame at most (default 8)")
      ->check(integerIn(1, 4096));
}

std::filesystem::path imageryCacheFolder(const std::string& input) {
  const std::filesystem::path beside = std::filesystem::absolute(input + ".imagery");
  std::error_code ec;
  if (std::filesystem::is_directory(beside, ec) ? access(beside.c_str(), W_OK) == 0
                                                : access(beside.parent_path().c_str(), W_OK) == 0) {
    return beside;
  }
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  const char* home = std::getenv("HOME");
  const std::filesystem::path base = xdg && *xdg ? std::filesystem::path(xdg)
                                     : home && *home ? std::filesystem::path(home) / ".cache"
                                                     : std::filesystem::temp_directory_path();
  return base / "tellus" / "imagery";
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
