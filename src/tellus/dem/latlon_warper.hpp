#pragma once
// Resamples several DEM sources at once onto a regular latitude/longitude point grid, with
// GDAL's warper: the global store's builder (tiles/global_store_builder.hpp) fills each tile
// this way.
//
// Contract of warp(): sample (i, j) is the point (north - j * step, west + i * step), degrees on
// WGS84. Each source is warped on its own (bilinear, exact transformer, no overviews, and the
// kernel fixed at one source pixel: XSCALE = YSCALE = 1), so a point's value never depends on
// the grid it is asked for: the same point in a coarse and a fine tile, or on the shared edge of
// two tiles, gets the same bits. Sources are given finest first; a point takes the first source
// that has a valid value there (inside it, not nodata), else NaN. Heights are in metres as the
// sources give them (above the geoid for SRTM, BIL and ETOPO), with each band's scale and offset
// applied.
//
// Edge blending (open()'s edgeBlendM > 0): a source that does not cover the globe fades into the
// sources after it over a band of that many metres inside its outermost sample centres, so that
// a fine DEM inserted into a coarse global one meets it without a cliff. The weight of a source
// at a point is smoothstep(d / edgeBlendM), d the distance in metres from the point to the nearest
// edge of the source's sample area, measured in the source's own grid (a projected source's
// edges are its grid's edges, not its latitude/longitude box). A point takes
// sum_k w_k * prod_{j<k} (1 - w_j) * value_k over the sources in order, divided by the weights'
// sum where no later source completes it. The weight depends on the point alone, so the
// contract above still holds. Holes inside a source (nodata) are not blended: they fall through
// to the next source as before.
//
// A LatLonWarper holds its own GDAL dataset handles: use one per thread. It opens a source the
// first time a warp needs it and keeps at most 64 open (the least recently used is closed), so a
// planet of 14,000 SRTM tiles costs each thread only the files its tiles touch.
#include <filesystem>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_encoding.hpp"

namespace tellus {

struct LatLonBox {
  double westDeg = 0.0, southDeg = 0.0, eastDeg = 0.0, northDeg = 0.0;
};

struct LatLonSource {
  std::filesystem::path path;  // the input as given: what messages and a store's metadata name
  // An RGB-encoded input (Terrain-RGB, Terrarium) is decoded with `encoding` into a Float32
  // copy before warping (writeDecodedHeightsCopy); `readPath` is what GDAL opens: `path`
  // itself, or that copy.
  HeightEncoding encoding = HeightEncoding::Plain;
  std::filesystem::path readPath;
  // The area the source's sample centres span (what bilinear interpolation can reach), and
  // that of its pixels (half a pixel more on each side), degrees.
  LatLonBox sampleBox;
  LatLonBox pixelBox;
  double spacingDeg = 0.0;   // the finer of its two sample spacings, degrees
  bool coversGlobe = false;  // spans all longitudes and latitudes
  bool assumedWgs84 = false;  // it had no CRS and is taken as WGS 84 latitude/longitude
  int width = 0, height = 0;
};

// Opens an input with GDAL and describes where it lies. An 8-bit image of 3 or 4 bands is an
// RGB-encoded height raster read with `rgbEncoding` (its readPath stays to be set to a decoded
// copy by the caller). Errors name the file: not a raster, several bands that are not an
// RGB-encoded raster, an RGB image with rgbEncoding Plain, no georeferencing, a rotated grid, a CRS
// that does not convert to WGS84, no CRS on a grid that is not in degrees (a grid without CRS
// whose cells are under a degree and inside the globe's longitudes and latitudes, as SRTM's BIL
// tiles, is taken as WGS 84 with a warning).
Result<LatLonSource> describeLatLonSource(const std::filesystem::path& path,
                                          HeightEncoding rgbEncoding = HeightEncoding::Plain);

class LatLonWarper {
 public:
  // `sources` finest first (the priority of warp()). With `zeroYieldsToSeaFloor`, a value of
  // exactly 0 m (how SRTM and most land DEMs store the sea) is kept only where no later source
  // has a value below 0 m there: the sea floor of a coarser source (ETOPO's bathymetry) shows
  // through a finer land source's flat sea, with the finer source's coastline.
  // `edgeBlendM`: the width of the band over which each source fades into the later ones
  // (above), metres; 0 keeps every source's values up to its edge.
  static Result<std::unique_ptr<LatLonWarper>> open(std::vector<LatLonSource> sources,
                                                    bool zeroYieldsToSeaFloor = false,
                                                    double edgeBlendM = 0.0);
  ~LatLonWarper();
  LatLonWarper(const LatLonWarper&) = delete;
  LatLonWarper& operator=(const LatLonWarper&) = delete;

  const std::vector<LatLonSource>& sources() const;
  // How many finite values the warps of this warper have taken from source `source` so far
  // (a source of nothing but nodata, NaN or infinities gives none).
  std::uint64_t finiteValuesFrom(int source) const;

  // Fills `out` (columns * rows, row-major, row 0 north) from the sources listed in `use`
  // (indices into sources(), in priority order); NaN where none has a value. `progress`, when
  // given, is called with the fraction of each source's warp done (0 to 1, several times a
  // source; GDAL's warper reads a shallow tile's sources at full resolution, which takes long).
  Status warp(double westDeg, double northDeg, double stepDeg, int columns, int rows,
              std::span<const int> use, std::span<float> out,
              const std::function<void(int source, double fraction)>& progress = {});

 private:
  struct Impl;
  explicit LatLonWarper(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace tellus
