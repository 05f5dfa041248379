#pragma once
// `tellus export STORE --gltf out.glb`: an adaptive triangle mesh of a region of a store within
// a given error, as one binary glTF 2.0 file (tinygltf): positions (metres), normals, optional
// hypsometric vertex colours, 32-bit indices from 65,536 vertices (16-bit below), in
// meshoptimizer's vertex-cache order. Positions are in a local east-north-up frame at the
// region's centre, computed per sample from its longitude, latitude and height through ECEF (no
// single ground spacing; the Earth's curvature included); glTF's axes: x east, y up, z south.
// The node's extras give the frame's origin, the matrix from the glTF frame to ECEF and the
// store's CRS. The mesh is built from the finest store level whose window fits the sample
// budget, by greedy insertion (greedy_tin.hpp) until every sample of that level is within the
// bound in 3-D. Written through a temporary file: never a half-written .glb.
#include <cstdint>
#include <filesystem>
#include <optional>

#include "tellus/core/result.hpp"
#include "tellus/export/lonlat_sampler.hpp"
#include "tellus/tiles/tile_store.hpp"

namespace tellus {

struct GltfExportOptions {
  std::optional<LonLatBox> region;  // WGS84 degrees; the whole store when unset
  double maxErrorM = 1.0;           // error bound (3-D), metres
  std::uint64_t maxSamples = std::uint64_t(4) << 20;  // budget of the window read, samples
  bool hypsometricColours = false;  // COLOR_0 from the hypsometric ramp
  bool quantize = false;            // KHR_mesh_quantization (glb_writer.hpp)
  // A georeferenced RGB image (any CRS GDAL and PROJ read) draped as the base colour: warped to
  // the region's longitude/latitude box (grey where it has no pixel), sides of powers of two:
  // the longest textureMaxSide rounded down to one, the other the nearest to the box's ground
  // aspect; embedded as a JPEG and mapped by TEXCOORD_0. Empty: none.
  std::filesystem::path texture;
  int textureMaxSide = 2048;
};

struct GltfExportReport {
  int storeLevel = 0;
  int width = 0, height = 0;   // window, samples
  std::uint64_t vertices = 0;
  std::uint64_t triangles = 0;
  double maxErrorM = 0.0;      // 3-D, measured against the window's samples (of storeLevel)
  std::uint64_t bytes = 0;     // of the .glb
  double spacingXM = 0.0, spacingYM = 0.0;  // the window's sample spacing
  float minHeightM = 0.0f, maxHeightM = 0.0f;
  double originLonDeg = 0.0, originLatDeg = 0.0;  // the local frame's origin (0 m)
  int textureWidth = 0, textureHeight = 0;        // 0: no texture
  double textureCoverage = 0.0;                   // of the texture's pixels the image covers
};

// Errors: a region outside the store or of fewer than 2 x 2 samples, a store without
// georeferencing (with a region), a bound that is negative or not finite, write failures.
Result<GltfExportReport> exportGltf(const TileStore& store, const std::filesystem::path& output,
                                    const GltfExportOptions& options);

// Reads the samples [col0, col0 + width) x [row0, row0 + height) of a store level (row 0 north)
// from the tiles that cover them.
Result<HeightGrid> readStoreWindow(const TileStore& store, int level, int col0, int row0,
                                   int width, int height);

}  // namespace tellus
