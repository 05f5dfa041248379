// Writes seed inputs for the fuzz targets into OUTPUT_FOLDER/<target kind>/:
//   <codec>/     valid encodings of tiles of several shapes, real 257 x 257 ones included, each
//                behind the decoder targets' header (width, height, maxErrorSteps)
//   store/       valid stores of every codec: 33 x 33 samples in 16-cell tiles, 513 x 513
//                samples in real 256-cell tiles, and a small global store (two roots, a child)
//                samples in real 256-cell tiles (2 x 2 tiles of 257 x 257 and their parent)
//   keyframes/   keyframe JSON files as tellus view records them, and edge cases
//   dem/         small rasters (GeoTIFF of several types with nodata, scale and georeferencing,
//                16-bit PNG, Terrain-RGB PNG, ASCII grid) behind the DEM target's two bytes
//   stack/       small .tstack files (one and several layers a stack, an overhang, a cave)
//   bdam/        BDAM patch files of a small hill (fine and coarse leaves)
//   metadata/    the JSON metadata of the flat and global seed stores behind a kind byte
//   http/        answers to a range request: good, redirected, refused, short, long
//   qmesh/       quantized-mesh tiles, with and without normals, 16-bit and 32-bit indices
//   terrainmesh/ grids behind the mesh target's header (sides, flags, bound)
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <cpl_vsi.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include "tellus/formats/bdam/bdam_file.hpp"
#include "tellus/formats/bdam/bdam_patches.hpp"
#include "tellus/export/quantized_mesh.hpp"
#include "tellus/formats/stacks/material_stack.hpp"
#include "tellus/formats/stacks/stack_aggregation.hpp"
#include "tellus/formats/stacks/stack_file.hpp"
#include "tellus/tiles/global_store_metadata.hpp"
#include "tellus/tiles/tile_codec.hpp"
#include "tellus/tiles/tile_store_writer.hpp"

namespace fs = std::filesystem;
using namespace tellus;

namespace {

constexpr std::uint32_t kMaxErrorSteps = 3;

std::vector<std::int32_t> hill(TileShape shape, int seed) {
  std::vector<std::int32_t> v(shape.sampleCount());
  for (int j = 0; j < shape.height; ++j)
    for (int i = 0; i < shape.width; ++i)
      v[std::size_t(j * shape.width + i)] = std::int32_t(
          500.0 * std::sin(0.2 * i + seed) * std::cos(0.15 * j) + 37 * ((i * j + seed) % 7));
  return v;
}

bool writeBytes(const fs::path& path, const void* data, std::size_t size) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return false;
  const bool written = std::fwrite(data, 1, size, f) == size;
  return std::fclose(f) == 0 && written;
}

// The value fuzz_codec.cpp reads as a tile side of `side` samples.
std::uint16_t fuzzTileSide(int side) {
  if (side <= 64) return std::uint16_t(side - 1);
  static constexpr std::array<int, 9> kStoreSides = {17, 33, 65, 129, 257, 513, 1025, 2049, 4097};
  for (std::uint16_t v = 0xF000;; ++v) {
    if (kStoreSides[v % kStoreSides.size()] == side) return v;
  }
}

template <typename T>
void appendLittleEndian(std::vector<std::byte>& out, T value) {
  const auto* bytes = reinterpret_cast<const std::byte*>(&value);
  out.insert(out.end(), bytes, bytes + sizeof(T));
}

// A gentle slope with a few bumps: real tile sizes whose encodings stay within the fuzzers'
// 4 KiB input limit, so full-size decoding is reached while most runs stay fast.
std::vector<std::int32_t> slope(TileShape shape) {
  std::vector<std::int32_t> v(shape.sampleCount());
  for (int j = 0; j < shape.height; ++j)
    for (int i = 0; i < shape.width; ++i)
      v[std::size_t(j * shape.width + i)] = 100 + i / 8 + j / 16 + ((i * 7 + j) % 97 == 0 ? 5 : 0);
  return v;
}

bool writeCodecSeeds(const fs::path& root) {
  for (const std::string& name : codecNames()) {
    fs::create_directories(root / name);
    auto codec = makeCodec(name, {.maxErrorSteps = kMaxErrorSteps, .zstdLevel = 3});
    int index = 0;
    for (TileShape shape :
         {TileShape{17, 17}, TileShape{5, 9}, TileShape{33, 2}, TileShape{257, 257}}) {
      std::vector<std::byte> bytes;
      appendLittleEndian(bytes, fuzzTileSide(shape.width));
      appendLittleEndian(bytes, fuzzTileSide(shape.height));
      appendLittleEndian(bytes, kMaxErrorSteps);
      const bool real = shape.width > 64;
      if (!codec.value()->encode(real ? slope(shape) : hill(shape, index), shape, bytes)) {
        return false;
      }
      const fs::path file = root / name / ("seed" + std::to_string(index++));
      if (!writeBytes(file, bytes.data(), bytes.size())) return false;
    }
  }
  return true;
}

// A metadata seed: the kind byte of fuzz_store_metadata.cpp (0 flat, 1 global), then the JSON.
bool writeMetadataSeed(const fs::path& file, std::uint8_t kind, const std::string& json) {
  std::string bytes(1, char(kind));
  bytes += json;
  return writeBytes(file, bytes.data(), bytes.size());
}


// A store of `codec` over width x height samples in tileSize-cell tiles.
bool writeStoreSeed(const fs::path& file, const std::string& codecName, int size, int tileSize) {
  auto codec = makeCodec(codecName, {.maxErrorSteps = kMaxErrorSteps, .zstdLevel = 3});
  if (!codec) return false;
  StoreMetadata m;
  m.layout = PyramidLayout::create(size, size, tileSize).value();
  m.codec = codecName;
  m.maxErrorSteps = codec.value()->lossless() ? 0 : kMaxErrorSteps;
  m.maxErrorM = m.maxErrorSteps;
  m.minHeightM = -1000.0f;  // holds every tile's range (checked by the reader)
  m.maxHeightM = 1000.0f;
  m.producer = "make_seed_corpus";
  auto writer = TileStoreWriter::create(file, codec.value()->id());
  if (!writer) return false;
  for (int level = 0; level < m.layout.levelCount(); ++level) {
    for (int y = 0; y < m.layout.tilesY(level); ++y) {
      for (int x = 0; x < m.layout.tilesX(level); ++x) {
        std::vector<std::byte> payload;
        const TileShape shape = m.layout.tileShape();
        const std::vector<std::int32_t> heights =
            shape.width > 64 ? slope(shape) : hill(shape, level + x + y);
        if (!codec.value()->encode(heights, m.layout.tileShape(), payload)) return false;
        const float geometricError = level == 0 ? 0.0f : 5.0f;
        const auto [lo, hi] = std::minmax_element(heights.begin(), heights.end());
        if (!writer.value()->append({level, x, y}, payload,
                                    {float(*lo), float(*hi), geometricError})) {
          return false;
        }
      }
    }
  }
  if (!writer.value()->finish(m)) return false;
  return writeMetadataSeed(file.parent_path().parent_path() / "metadata" / (file.stem().string() + ".json"), 0,
                           metadataToJson(m));
}

// A global store of `codec`: both 16-cell roots and one depth-1 child of the eastern one.
bool writeGlobalStoreSeed(const fs::path& file, const std::string& codecName) {
  auto codec = makeCodec(codecName, {.maxErrorSteps = kMaxErrorSteps, .zstdLevel = 3});
  if (!codec) return false;
  GlobalStoreMetadata m;
  m.tileCells = 16;
  m.deepestDepth = 1;
  m.tilesPerDepth = {2, 1};
  m.codec = codecName;
  m.quantumM = 1.0;
  m.maxErrorSteps = codec.value()->lossless() ? 0 : kMaxErrorSteps;
  m.maxErrorM = m.maxErrorSteps;
  m.minHeightM = -1000.0f;
  m.maxHeightM = 1000.0f;
  m.producer = "make_seed_corpus";
  m.sources = {{"seed.tif", {-180.0, -90.0, 180.0, 90.0}, 5.625, 1}};
  auto writer = TileStoreWriter::create(file, codec.value()->id());
  if (!writer) return false;
  const TileShape shape{17, 17};
  const int keys[3][3] = {{0, 0, 0}, {0, 1, 0}, {1, 2, 0}};
  for (const auto& k : keys) {
    std::vector<std::byte> payload;
    const std::vector<std::int32_t> heights = hill(shape, k[1]);
    if (!codec.value()->encode(heights, shape, payload)) return false;
    const auto [lo, hi] = std::minmax_element(heights.begin(), heights.end());
    const float error = (k[0] == 0 && k[1] == 1) ? 5.0f : 0.0f;  // only (0, 1, 0) has a child
    if (!writer.value()->append({k[0], k[1], k[2]}, payload, {float(*lo), float(*hi), error})) {
      return false;
    }
  }
  if (!writer.value()->finishWithMetadata(globalMetadataToJson(m))) return false;
  return writeMetadataSeed(file.parent_path().parent_path() / "metadata" / (file.stem().string() + ".json"), 1,
                           globalMetadataToJson(m));
}

bool writeKeyframeSeeds(const fs::path& folder) {
  const std::vector<std::string> seeds = {
      R"({"keyframes": [
 {"time": 0, "position": [20000, 20000, 3000], "yaw": 45, "pitch": -20, "fov": 55},
 {"time": 4, "position": [45000, 50000, 2500], "yaw": 60, "pitch": -15, "fov": 55},
 {"time": 8, "position": [60000, 80000, 2200], "yaw": 30, "pitch": -12, "fov": 55}]})",
      R"({"keyframes": [{"time": 0, "position": [0, 0, 10], "yaw": 359, "pitch": -90},
 {"time": 1e-3, "position": [1, 1, 10], "yaw": 1, "pitch": 90, "fov": 0.01}]})",
      R"({"keyframes": [{"time": -5, "position": [1e9, -1e9, 0], "yaw": -1e6, "pitch": 0,
 "fov": 179}, {"time": 1e9, "position": [0, 0, 0], "yaw": 1e6, "pitch": 0}]})",
  };
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    const fs::path file = folder / ("seed" + std::to_string(i) + ".json");
    if (!writeBytes(file, seeds[i].data(), seeds[i].size())) return false;
  }
  return true;
}

// Creates a raster with `driver` in /vsimem/, returns its bytes behind the DEM target's two
// bytes (name index, encoding).
bool writeRasterSeed(const fs::path& file, const char* driverName, GDALDataType type, int bands,
                     std::uint8_t nameIndex, std::uint8_t encoding, bool nodataAndScale) {
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName(driverName);
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  if (!driver || !mem) return false;
  GDALDataset* source = mem->Create("", 17, 13, bands, type, nullptr);
  std::array<double, 6> gt = {127.0, 0.001, 0.0, 37.5, 0.0, -0.001};
  source->SetGeoTransform(gt.data());
  OGRSpatialReference srs;
  srs.importFromEPSG(4326);
  source->SetSpatialRef(&srs);
  for (int b = 1; b <= bands; ++b) {
    std::vector<double> values(17 * 13);
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = double((i * 37 + b * 11) % 251);
    if (nodataAndScale) values[20] = -9999.0;
    GDALRasterBand* band = source->GetRasterBand(b);
    if (band->RasterIO(GF_Write, 0, 0, 17, 13, values.data(), 17, 13, GDT_Float64, 0, 0) !=
        CE_None) {
      return false;
    }
    if (nodataAndScale) {
      band->SetNoDataValue(-9999.0);
      band->SetScale(0.5);
      band->SetOffset(10.0);
    }
  }
  const std::string path = "/vsimem/seed-raster";
  GDALDataset* copy = driver->CreateCopy(path.c_str(), source, FALSE, nullptr, nullptr, nullptr);
  GDALClose(source);
  if (!copy) return false;
  GDALClose(copy);
  vsi_l_offset length = 0;
  GByte* bytes = VSIGetMemFileBuffer(path.c_str(), &length, FALSE);
  std::vector<std::uint8_t> out = {nameIndex, encoding};
  out.insert(out.end(), bytes, bytes + length);
  VSIUnlink(path.c_str());
  return writeBytes(file, out.data(), out.size());
}

bool writeDemSeeds(const fs::path& folder) {
  GDALAllRegister();
  // Name indices follow fuzz_dem_load.cpp: 0 .tif, 2 .png, 3 .asc.
  return writeRasterSeed(folder / "int16.tif", "GTiff", GDT_Int16, 1, 0, 0, false) &&
         writeRasterSeed(folder / "float-nodata-scale.tif", "GTiff", GDT_Float32, 1, 0, 0, true) &&
         writeRasterSeed(folder / "uint16.png", "PNG", GDT_UInt16, 1, 2, 0, false) &&
         writeRasterSeed(folder / "terrain-rgb.png", "PNG", GDT_Byte, 3, 2, 1, false) &&
         writeRasterSeed(folder / "terrarium.png", "PNG", GDT_Byte, 4, 2, 2, false) &&
         writeRasterSeed(folder / "grid.asc", "AAIGrid", GDT_Float32, 1, 3, 0, true);
}



// Stack files: a terrace of one layer a stack, and stacks with an overhang and a cave.
bool writeStackSeeds(const fs::path& folder) {
  for (int variant = 0; variant < 3; ++variant) {
    const int w = variant == 0 ? 8 : 13, h = variant == 0 ? 8 : 9;
    std::vector<std::vector<StackLayer>> columns;
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        std::vector<StackLayer> column{{0.0f, 10.0f + float((x * 3 + y * 5) % 7), StackMaterial(1)}};
        if (variant >= 1 && x % 4 == 1) column.push_back({22.0f, 25.0f, StackMaterial(2)});  // overhang
        if (variant == 2 && y % 3 == 0) {
          column.front().topM = 4.0f;  // a cave between 4 and 7 m
          column.insert(column.begin() + 1, StackLayer{7.0f, 18.0f, StackMaterial(3)});
        }
        columns.push_back(std::move(column));
      }
    }
    Result<StackTerrain> terrain = StackTerrain::fromColumns(w, h, 2.0, columns);
    if (!terrain) return false;
    if (!writeStackFile(folder / ("seed" + std::to_string(variant) + ".tstack"),
                        buildStackPyramid(std::move(terrain.value())))) {
      return false;
    }
  }
  return true;
}

// BDAM patch files of a 65 x 49 hill: fine leaves (many small patches) and coarse ones.
bool writeBdamSeeds(const fs::path& folder) {
  HeightGrid grid(65, 49);
  grid.spacingXM = grid.spacingYM = 30.0;
  for (int r = 0; r < grid.height; ++r) {
    for (int c = 0; c < grid.width; ++c) {
      grid.at(c, r) = float(300.0 * std::sin(0.1 * c) * std::cos(0.13 * r) + 2.0 * ((c * r) % 5));
    }
  }
  for (const int leaf : {6, 9}) {
    bdam::BuildSettings settings;
    settings.leafLog2 = leaf;
    settings.patchTriangles = 32;
    Result<bdam::Hierarchy> hierarchy = bdam::buildHierarchy(grid, settings);
    if (!hierarchy || !bdam::writePatchFile(hierarchy.value(), folder / ("leaf" + std::to_string(leaf) + ".bdam"))) {
      return false;
    }
  }
  return true;
}

// Answers to a request of bytes 100..103 (the target's offset and length fields first).
bool writeHttpSeeds(const fs::path& folder) {
  const std::vector<std::pair<std::string, std::string>> answers = {
      {"good", "HTTP/1.1 206 Partial Content\r\nContent-Range: bytes 100-103/5000\r\nContent-Length: 4\r\n\r\nabcd"},
      {"redirected", "HTTP/1.1 302 Found\r\nLocation: /b\r\n\r\nHTTP/1.1 206 Partial Content\r\n"
                     "content-range: bytes 100-103/5000\r\n\r\nabcd"},
      {"no-ranges", "HTTP/1.1 200 OK\r\nContent-Length: 5000\r\n\r\nabcdefgh"},
      {"missing", "HTTP/1.1 404 Not Found\r\n\r\n"},
      {"short", "HTTP/1.1 206 Partial Content\r\nContent-Range: bytes 100-103/5000\r\n\r\nab"},
      {"long", "HTTP/1.1 206 Partial Content\r\nContent-Range: bytes 100-103/5000\r\n\r\nabcdefgh"},
      {"star", "HTTP/1.1 206 Partial Content\r\nContent-Range: bytes 100-103/*\r\n\r\nabcd"},
      {"elsewhere", "HTTP/1.1 206 Partial Content\r\nContent-Range: bytes 0-3/5000\r\n\r\nabcd"},
  };
  for (const auto& [name, text] : answers) {
    std::vector<std::byte> bytes;
    appendLittleEndian<std::uint32_t>(bytes, 100);
    appendLittleEndian<std::uint16_t>(bytes, 3);  // length 1 + 3
    for (char c : text) bytes.push_back(std::byte(c));
    if (!writeBytes(folder / (name + ".http"), bytes.data(), bytes.size())) return false;
  }
  return true;
}

// Quantized-mesh tiles: two triangles; a fan of many vertices (32-bit indices past 65536
// vertices is too large for a seed: 16-bit only) with oct-encoded normals.
bool writeQuantizedMeshSeeds(const fs::path& folder) {
  QuantizedMeshTile square;
  square.header.centreEcef = {-3.0e6, 4.0e6, 3.8e6};
  square.header.minHeightM = 10.0f;
  square.header.maxHeightM = 900.0f;
  square.header.boundingSphereCentreEcef = square.header.centreEcef;
  square.header.boundingSphereRadiusM = 5000.0;
  square.header.horizonOcclusionPoint = {-0.5, 0.6, 0.6};
  square.u = {0, 32767, 0, 32767};
  square.v = {0, 0, 32767, 32767};
  square.height = {0, 1000, 20000, 32767};
  square.indices = {0, 1, 2, 2, 1, 3};
  square.westEdge = {0, 2};
  square.southEdge = {0, 1};
  square.eastEdge = {1, 3};
  square.northEdge = {2, 3};
  QuantizedMeshTile fan = square;
  fan.u.clear(), fan.v.clear(), fan.height.clear(), fan.indices.clear();
  fan.westEdge = {0}, fan.southEdge = {0}, fan.eastEdge.clear(), fan.northEdge.clear();
  fan.u.push_back(0), fan.v.push_back(0), fan.height.push_back(0);
  for (int k = 1; k <= 200; ++k) {
    fan.u.push_back(std::uint16_t(k * 150)), fan.v.push_back(std::uint16_t((k * 97) % 32768));
    fan.height.push_back(std::uint16_t((k * 131) % 32768));
    if (k >= 2) fan.indices.insert(fan.indices.end(), {0u, std::uint32_t(k - 1), std::uint32_t(k)});
  }
  for (std::size_t k = 0; k < fan.u.size(); ++k) fan.octNormals.push_back({std::uint8_t(k), std::uint8_t(255 - k)});
  for (const auto& [name, tile] : {std::pair{"square", square}, std::pair{"fan-normals", fan}}) {
    Result<std::vector<std::byte>> bytes = encodeQuantizedMesh(tile);
    if (!bytes || !writeBytes(folder / (std::string(name) + ".terrain"), bytes->data(), bytes->size())) return false;
  }
  return true;
}

// Grids behind fuzz_terrain_mesh.cpp's header: a ridge, a flat field, a spike, a locked border.
bool writeTerrainMeshSeeds(const fs::path& folder) {
  for (int variant = 0; variant < 4; ++variant) {
    std::vector<std::byte> bytes;
    const std::uint8_t side = variant == 3 ? 7 : 5;  // 9 or 7 samples
    bytes.push_back(std::byte(side));
    bytes.push_back(std::byte(side));
    bytes.push_back(std::byte(variant == 3 ? 1 : 0));
    appendLittleEndian<std::uint16_t>(bytes, std::uint16_t(variant == 1 ? 0 : 20));  // 0 or 2 m
    const int n = side + 2;
    for (int i = 0; i < n * n; ++i) {
      const int x = i % n, y = i / n;
      const std::int16_t h = variant == 1   ? 200
                             : variant == 2 ? std::int16_t(x == n / 2 && y == n / 2 ? 3000 : 0)
                                            : std::int16_t(400.0 * std::sin(0.4 * x) + 30 * y);
      appendLittleEndian<std::int16_t>(bytes, h);
    }
    if (!writeBytes(folder / ("grid" + std::to_string(variant) + ".bin"), bytes.data(), bytes.size())) return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_seed_corpus OUTPUT_FOLDER\n");
    return 2;
  }
  const fs::path root = argv[1];
  for (const char* folder : {"store", "keyframes", "dem", "stack", "bdam", "metadata", "http", "qmesh", "terrainmesh"}) {
    fs::create_directories(root / folder);
  }
  if (!writeCodecSeeds(root)) return 1;
  for (const std::string& codec : codecNames()) {
    if (!writeStoreSeed(root / "store" / (codec + "-small.tstore"), codec, 33, 16) ||
        !writeStoreSeed(root / "store" / (codec + "-257.tstore"), codec, 513, 256) ||
        !writeGlobalStoreSeed(root / "store" / (codec + "-global.tstore"), codec)) {
      std::fprintf(stderr, "make_seed_corpus: cannot write the %s stores\n", codec.c_str());
      return 1;
    }
  }
  if (!writeKeyframeSeeds(root / "keyframes")) return 1;
  if (!writeDemSeeds(root / "dem")) {
    std::fprintf(stderr, "make_seed_corpus: cannot write the raster seeds\n");
    return 1;
  }
  if (!writeStackSeeds(root / "stack") || !writeBdamSeeds(root / "bdam") || !writeHttpSeeds(root / "http") ||
      !writeQuantizedMeshSeeds(root / "qmesh") || !writeTerrainMeshSeeds(root / "terrainmesh")) {
    std::fprintf(stderr, "make_seed_corpus: cannot write the stack, BDAM, HTTP or mesh seeds\n");
    return 1;
  }
  return 0;
}
