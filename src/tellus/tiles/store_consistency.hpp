#pragma once
// Whether a flat store's tiles are where they belong: checksums and index statistics can be
// recomputed by whoever rewrites a file, so `tellus verify` also checks what only the right
// tile in the right place satisfies (pyramid_layout.hpp):
//   - neighbours of one level share their edge samples (tile (x, y)'s last column is tile
//     (x + 1, y)'s first, its last row tile (x, y + 1)'s first);
//   - every level nests in the next: level L's sample at even position (2i, 2j) is level L + 1's
//     sample (i, j), wherever both lie on the data (level-0 positions inside the data).
// Lossless codecs must agree exactly; codecs that bound their error agree within twice the
// bound; a codec that bounds nothing (fractal without residual) is not checked.
//
// Use: addTile() for every tile as it is decoded (any thread, each record once), then check().
// Memory: six lines of samples per tile (rows and columns 0, n/2 and n), about 6 KiB for
// 257 x 257 tiles.
#include <cstdint>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "tellus/tiles/tile_store.hpp"

namespace tellus {

class StoreConsistency {
 public:
  explicit StoreConsistency(const TileStore& store);

  // The largest difference allowed between two stored copies of one sample, in quantum steps;
  // nullopt when the codec bounds nothing (no check).
  std::optional<std::int64_t> toleranceSteps() const { return tolerance_; }

  // Keeps the lines check() compares. `samples` is the decoded tile (quantum steps).
  void addTile(const TileRecord& record, std::span<const std::int32_t> samples);

  // The problems found, one sentence each naming the store and the tiles, at most `limit`.
  std::vector<std::string> check(std::size_t limit) const;

 private:
  // Rows 0, n/2, n then columns 0, n/2, n of one tile.
  struct Lines {
    std::vector<std::int32_t> line[6];
  };
  const Lines* linesOf(TileKey key) const;
  void compareEdges(TileKey key, std::vector<std::string>& problems) const;
  void compareWithParent(TileKey key, std::vector<std::string>& problems) const;
  std::string where(TileKey key) const;

  const TileStore& store_;
  int n_ = 0;
  std::optional<std::int64_t> tolerance_;
  std::vector<Lines> lines_;  // by record index; empty vectors: not added
};

}  // namespace tellus
