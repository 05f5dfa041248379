#pragma once
// Reads a global store: a .tstore container (store_format.hpp, store_container.hpp) whose tiles
// follow the geographic tiling (global_tiling.hpp) instead of a flat pyramid. Index records
// hold (depth, x, y) in (level, x, y).
//
// The pyramid is sparse: both root tiles are always stored, and a tile is stored only when a
// source is fine enough to feed it (global_store_builder.hpp); a tile that is not stored is its
// deepest stored ancestor, upsampled (bilinear on the ancestor's samples, which is exactly what
// that ancestor draws there). Every stored tile's parent is stored.
//
// A stored sample is the same height in every tile that holds its point: on the edge two tiles
// share, and in a coarse tile and its finer descendants (the build warps each point the same way
// whatever the tile). A tile's geometric error is the largest |h - I| over the samples h of its
// stored descendants, I being the tile's bilinear surface, exactly as for flat stores.
//
// The file is untrusted: open() validates header, metadata and index; each tile read checks its
// checksum. Thread-safe after open().
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <unordered_map>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/tiles/byte_source.hpp"
#include "tellus/tiles/store_container.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/tiles/global_store_metadata.hpp"
#include "tellus/tiles/global_tiling.hpp"
#include "tellus/tiles/tile_codec.hpp"
#include "tellus/tiles/tile_record.hpp"

namespace tellus {

class GlobalStore {
 public:
  static Result<std::shared_ptr<GlobalStore>> open(const std::filesystem::path& path);
  // The same from its container, already read (by a caller that looked at its format first).
  static Result<std::shared_ptr<GlobalStore>> open(const std::filesystem::path& path, StoreContainer container);
  ~GlobalStore();
  GlobalStore(const GlobalStore&) = delete;
  GlobalStore& operator=(const GlobalStore&) = delete;

  const std::filesystem::path& path() const { return path_; }
  const GlobalStoreMetadata& metadata() const { return metadata_; }
  const TileCodec& codec() const { return *codec_; }
  std::uint64_t fileBytes() const { return fileBytes_; }
  const ByteSource& source() const { return *source_; }
  int tileCells() const { return metadata_.tileCells; }
  TileShape tileShape() const { return {tileCells() + 1, tileCells() + 1}; }
  // All stored tiles, sorted by (depth, y, x); key.level is the depth.
  std::span<const TileRecord> records() const { return records_; }
  // nullptr when the tile is not stored.
  const TileRecord* find(GeoTileKey key) const;
  // The tile itself when stored, else its deepest stored ancestor (a root at worst).
  GeoTileKey deepestStored(GeoTileKey key) const;
  bool hasStoredChildren(GeoTileKey key) const;

  // Reads, checks and decodes a stored tile (tileShape() samples, quantum steps / metres).
  Status readTile(GeoTileKey key, std::span<std::int32_t> samples) const;
  Status readTileMetres(GeoTileKey key, std::span<float> heights) const;

  // "tile 3/5/2 (depth/x/y)".
  static std::string describe(GeoTileKey key);
  static TileKey toTileKey(GeoTileKey key) { return {key.depth, key.x, key.y}; }
  static GeoTileKey toGeoKey(TileKey key) { return {key.level, key.x, key.y}; }

 private:
  GlobalStore() = default;

  std::filesystem::path path_;
  std::shared_ptr<ByteSource> source_;
  std::uint64_t fileBytes_ = 0;
  GlobalStoreMetadata metadata_;
  std::unique_ptr<TileCodec> codec_;
  std::vector<TileRecord> records_;
  std::unordered_map<TileKey, std::size_t, TileKeyHash> byKey_;
};

// A tile's bilinear surface, the one a tile draws: `heights` holds (cells + 1)^2 samples, row 0
// north; (u, v) is a fractional sample position (u east, v south), clamped into the tile's
// cells. What a missing tile is upsampled from and errors are measured against.
inline double tileSurfaceAt(std::span<const float> heights, int cells, double u, double v) {
  const int u0 = std::clamp(int(std::floor(u)), 0, cells - 1);
  const int v0 = std::clamp(int(std::floor(v)), 0, cells - 1);
  const double fu = u - u0, fv = v - v0;
  const std::size_t row = std::size_t(cells + 1);
  const float* p = heights.data() + std::size_t(v0) * row + std::size_t(u0);
  // In double throughout: at fu = 1 (a tile's last column) this gives p[1] exactly, so that
  // two tiles interpolating along their shared edge give the same bits.
  const double top = p[0] + (double(p[1]) - p[0]) * fu;
  const double bottom = p[row] + (double(p[row + 1]) - p[row]) * fu;
  return top + (bottom - top) * fv;
}

// The store's surface at a depth, one sample point at a time: where sample (column, row) of
// tile `key` (0..cells each, row 0 north) comes from. Inside a tile, from the tile's deepest
// stored source (upsampled by tileSurfaceAt where shallower). A sample on an edge or a corner
// belongs to every tile of key.depth that meets there, and the deepest source among them wins:
// the data over an ancestor's interpolation. Stored tiles agree where they meet and nest (tellus
// verify checks both), so under this rule the surface is one function of the point: tiles read
// it alike on their shared edges, and the surface of depth d equals that of depth d + 1 on their
// common sample points. Every reader that joins tiles uses it (readGlobalRegion, the harness's
// StoreSurface, the streaming globe renderers' blocks), so that they meet without cracks and measure the same truth.
struct StoreSampleSource {
  GeoTileKey source;         // the stored tile to read
  double u = 0.0, v = 0.0;   // the sample's position in its cells (tileSurfaceAt)
  double scale = 1.0;        // its cells per cell of key.depth: 2^-(key.depth - source.depth)
};
StoreSampleSource storeSampleSource(const GlobalStore& store, GeoTileKey key, int column, int row);

// True when `path` is a .tstore whose metadata says it is a global store.
bool isGlobalStore(const std::filesystem::path& path);

// WKT of WGS 84 latitude/longitude (EPSG:4326), for grids read from a global store.
extern const char* const kWgs84Wkt;

// The surface of `depth` over `box` (degrees; snapped outward to that depth's samples) as a
// latitude/longitude HeightGrid in metres, with its georeferencing (sample centres on the
// tiles' sample points). Missing tiles come from their deepest stored ancestor, upsampled; on
// tile edges the deepest source wins (storeSampleSource's rule). A box
// spanning all longitudes gives 2^(depth+1) * cells columns (lon -180 up to one step short of
// 180: the globe mesh closes the seam). Errors: an empty box, more than `maxSamples` samples.
Result<HeightGrid> readGlobalRegion(const GlobalStore& store, int depth, const GeoBounds& box,
                                    std::uint64_t maxSamples = std::uint64_t(1) << 28);

// The surface of the store over tile `key` (stored or not) at key.depth: its (cells + 1)^2
// samples as a latitude/longitude HeightGrid in metres, georeferenced like readGlobalRegion's.
// Inside, from key's deepest stored source; on its edges and corners, storeSampleSource's rule
// (the deepest source among the tiles meeting there), so two tiles of one depth read this way
// share their edges' heights exactly. Errors: a key outside the tiling, a tile that fails to read.
Result<HeightGrid> readGlobalTileSurface(const GlobalStore& store, GeoTileKey key);

}  // namespace tellus
