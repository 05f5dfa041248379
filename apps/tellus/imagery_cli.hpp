#pragma once
// --imagery and its budgets, shared by render, bench and view: imagery draped on every renderer
// (flat, globe, stack terrain) through one virtual texture (render/imagery/imagery_textures.hpp).
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/render/imagery/imagery_textures.hpp"

namespace tellus::cli {

struct ImageryCliOptions {
  std::vector<std::string> files;  // georeferenced RGB rasters, later ones on top
  double budgetMiB = 96.0;         // GPU memory for imagery pages
  int uploadsPerFrame = 8;         // pages transferred a frame at most
  bool any() const { return !files.empty(); }
};
void addImageryOptions(CLI::App* app, ImageryCliOptions& options);

// Where the pyramids of imagery draped on `input` (a DEM file or a store) are cached:
// INPUT.imagery/ beside it when that folder can be written, else the user's cache
// ($XDG_CACHE_HOME or ~/.cache, tellus/imagery).
std::filesystem::path imageryCacheFolder(const std::string& input);

// The virtual texture of `options.files` over the flat world of `flatGrid` (its
// georeferencing places them), or over the globe when it is null; nullptr without --imagery.
// Needs a current GL context.
Result<std::unique_ptr<ImageryTextures>> makeImagery(const ImageryCliOptions& options, const HeightGrid* flatGrid,
                                                     const std::string& input);

}  // namespace tellus::cli
