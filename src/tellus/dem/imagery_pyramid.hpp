#pragma once
// Large georeferenced imagery (seed 001's "Large Textures": a Landsat scene, aerial photographs,
// small decals) preprocessed once into a pyramid of square tiles, the file Tellus pages from
// with memory mapping so tile bytes go to the GPU without a copy of our own.
//
// The file (".timagery"): a 4096-byte header, then for every level 0 (full resolution) to
// levels - 1 (the whole image in one tile), its tiles row by row, north row first, each
// tileSize x tileSize RGBA8 texels, row 0 north. Level m is the image halved m times:
// ceil(width / 2^m) x ceil(height / 2^m) texels, each the average of the valid texels below it
// (alpha: the valid fraction; texels outside the image or the source's mask have alpha 0).
// Tile (x, y) of level m holds texels [x t, (x + 1) t) x [y t, (y + 1) t) of that level
// (t = tileSize), so a tile of level m covers the four tiles (2x .. 2x + 1, 2y .. 2y + 1) of
// level m - 1: the tiles form a quadtree over the image. Where the image lies: the source's
// geotransform (north-up, level-0 pixels) and CRS, kept in the header.
#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "tellus/core/mapped_file.hpp"
#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"

namespace tellus {

// A grid the source is resampled onto before the pyramid is built (GDAL's warper, bilinear):
// imagery in any CRS draped on a store in another. North-up, `width` x `height` pixels.
struct ImageryWarpGrid {
  std::string crsWkt;                 // the target CRS (a store's)
  std::array<double, 6> geoTransform{};
  int width = 0, height = 0;
};

struct ImageryBuildOptions {
  int tileSize = 256;  // texels a tile side (a power of two, 16 to 2048)
  int maxSide = 65536; // sources larger than this are refused
  // Resample onto this grid first (the source's own pixels when empty).
  std::optional<ImageryWarpGrid> warp = std::nullopt;
};

// The grid a source is draped on over a store's level-0 grid (`storeGeoref`, `dataWidth` x
// `dataHeight` samples, pixel-is-area): the store's CRS, the source's own resolution there
// (GDAL's suggestion), the part of the store the source covers, snapped to texels counted from
// the store's north-west corner, at most `maxSide` texels a side (coarser if it would be more).
// Errors name the source: no CRS on either side, no transformation, or no overlap.
// imageryGridOnGlobe: the same on the globe's latitude/longitude (WGS 84), snapped to texels
// counted from (180 W, 90 N), over the source's own footprint.
Result<ImageryWarpGrid> imageryGridOnGlobe(const std::filesystem::path& source, int maxSide = 65536);
Result<ImageryWarpGrid> imageryGridOnStore(const std::filesystem::path& source,
                                          const GeoReference& storeGeoref, int dataWidth,
                                          int dataHeight, int maxSide = 65536);

// Builds `output` from any raster GDAL reads with at least three 8-bit bands (red, green, blue;
// a fourth band or the source's mask gives validity), georeferenced north-up in any CRS PROJ
// knows (or, without a CRS, a grid within the globe's degrees: WGS 84 latitude/longitude, as
// drapes). Written atomically. Errors name the source: unreadable, not RGB bytes, rotated or
// missing georeferencing, too large, or a CRS that cannot be turned into latitude/longitude.
Status buildImageryPyramid(const std::filesystem::path& source, const std::filesystem::path& output,
                           const ImageryBuildOptions& options = {});

class ImageryPyramid {
 public:
  ImageryPyramid();
  ~ImageryPyramid();
  ImageryPyramid(ImageryPyramid&&) noexcept;
  ImageryPyramid& operator=(ImageryPyramid&&) noexcept;

  // Maps `path` and checks it: magic, version, sizes, and a file exactly as long as its tiles.
  static Result<ImageryPyramid> open(const std::filesystem::path& path);

  int tileSize() const { return tileSize_; }
  int width() const { return width_; }     // level-0 texels
  int height() const { return height_; }
  int levels() const { return levels_; }   // the last holds the whole image in one tile
  int levelWidth(int level) const;         // texels of a level
  int levelHeight(int level) const;
  int tilesX(int level) const;
  int tilesY(int level) const;
  // Tile (x, y) of `level`: tileSize^2 RGBA8 texels, row 0 north, straight from the mapping.
  std::span<const std::byte> tile(int level, int x, int y) const;

  // Where level-0 texel coordinates (x east, y south, 0..width x 0..height, pixel corners) lie:
  // WGS 84 latitude and longitude, degrees. Not thread-safe (the PROJ transformation).
  struct LatLon {
    double latDeg = 0.0, lonDeg = 0.0;
  };
  Result<LatLon> latLonAt(double x, double y) const;
  const std::filesystem::path& path() const { return path_; }
  // The level-0 grid in its CRS (GDAL geotransform, pixel corners) and that CRS (WKT; empty:
  // latitude/longitude degrees).
  const std::array<double, 6>& geoTransform() const { return geoTransform_; }
  const std::string& crsWkt() const { return crsWkt_; }
  std::uint64_t sourceBytes() const { return sourceBytes_; }
  std::int64_t sourceModifiedNs() const { return sourceModifiedNs_; }

 private:
  struct Transform;
  std::filesystem::path path_;
  MappedFile file_;
  int tileSize_ = 0, width_ = 0, height_ = 0, levels_ = 0;
  std::uint64_t sourceBytes_ = 0;
  std::int64_t sourceModifiedNs_ = 0;
  std::array<double, 6> geoTransform_{};
  std::string crsWkt_;
  std::unique_ptr<Transform> transform_;
};

// The cached pyramid of `source` in `cacheFolder` (NAME.timagery; NAME-KEY.timagery when
// warped, KEY a hash of the grid), built when missing or when it was built from a source of
// another size or modification time.
Result<ImageryPyramid> openCachedImageryPyramid(const std::filesystem::path& source,
                                                const std::filesystem::path& cacheFolder,
                                                const ImageryBuildOptions& options = {});

}  // namespace tellus
