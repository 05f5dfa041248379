// libFuzzer target: the adaptive mesh both exports build (tellus/export/terrain_mesh.hpp:
// glTF's and quantized-mesh's), from any height grid, then a quantized-mesh tile of it.
// Input: [width u8][height u8][flags u8][max error u16][heights i16...]: a grid of 2 to 9
// samples a side (the greedy insertion re-rates every sample of a triangle it splits, so larger
// grids cost milliseconds a run under the sanitizers: the cases live in the small ones), heights in half metres (the bytes repeat when short), a bound of 0 to 6553.5
// m, and (flag 1) a locked border. The mesh must keep its bound (measured again over every
// sample), cover the grid, and encode as a tile that decodes to the same vertices and triangles.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "fuzz_input.hpp"
#include "tellus/export/quantized_mesh.hpp"
#include "tellus/export/terrain_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  tellus::fuzz::FuzzInput input(data, size);
  const int width = 2 + input.take<std::uint8_t>() % 8, height = 2 + input.take<std::uint8_t>() % 8;
  const std::uint8_t flags = input.take<std::uint8_t>();
  const double maxErrorM = input.take<std::uint16_t>() * 0.1;
  const std::span<const std::byte> rest = input.rest();
  static std::vector<float> heights;
  heights.assign(std::size_t(width) * std::size_t(height), 0.0f);
  if (rest.size() >= 2) {
    const std::size_t values = rest.size() / 2;
    for (std::size_t i = 0; i < heights.size(); ++i) {
      std::int16_t v = 0;
      std::memcpy(&v, rest.data() + 2 * (i % values), 2);
      heights[i] = float(v) * 0.5f;
    }
  }
  const tellus::GridHeights grid{width, height, 30.0, 30.0, heights};
  tellus::Result<tellus::TerrainMesh> built =
      tellus::buildTerrainMesh(grid, {.maxErrorM = maxErrorM, .lockBorder = (flags & 1) != 0});
  if (!built) std::abort();  // every finite grid of 2 x 2 or more makes a mesh
  tellus::TerrainMesh& mesh = built.value();
  const double measured = tellus::measureVerticalError(grid, mesh.samples, mesh.indices);
  if (!(measured <= maxErrorM + 1e-3)) std::abort();
  tellus::orderForRendering(mesh);
  // As the quantized-mesh tiler lays it out: u, v over the lattice, heights over their range.
  tellus::QuantizedMeshTile tile;
  float lo = heights[mesh.samples[0]], hi = lo;
  for (std::uint32_t s : mesh.samples) lo = std::min(lo, heights[s]), hi = std::max(hi, heights[s]);
  for (std::size_t k = 0; k < mesh.samples.size(); ++k) {
    const int col = int(mesh.samples[k]) % width, row = int(mesh.samples[k]) / width;
    tile.u.push_back(std::uint16_t(std::lround(double(col) / (width - 1) * tellus::kQuantizedMeshMaxCoordinate)));
    tile.v.push_back(std::uint16_t(std::lround(double(row) / (height - 1) * tellus::kQuantizedMeshMaxCoordinate)));
    tile.height.push_back(hi > lo ? std::uint16_t(std::lround(double(heights[mesh.samples[k]] - lo) / double(hi - lo) *
                                                             tellus::kQuantizedMeshMaxCoordinate))
                                  : 0);
    if (col == 0) tile.westEdge.push_back(std::uint32_t(k));
    if (row == 0) tile.southEdge.push_back(std::uint32_t(k));
    if (col == width - 1) tile.eastEdge.push_back(std::uint32_t(k));
    if (row == height - 1) tile.northEdge.push_back(std::uint32_t(k));
  }
  tile.indices = mesh.indices;
  tellus::Result<std::vector<std::byte>> bytes = tellus::encodeQuantizedMesh(tile);
  if (!bytes) std::abort();
  tellus::Result<tellus::QuantizedMeshTile> back = tellus::decodeQuantizedMesh(bytes.value(), "fuzz mesh");
  if (!back || back->u != tile.u || back->v != tile.v || back->height != tile.height ||
      back->indices != tile.indices) {
    std::abort();
  }
  return 0;
}
