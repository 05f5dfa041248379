// Writes seed inputs for the fuzz targets into OUTPUT_FOLDER/<target kind>/:
//   <codec>/     valid encodings of tiles of several shapes, real 257 x 257 ones included, each
//                behind the decoder targets' header (width, height, maxErrorSteps)
//   store/       valid stores of every codec: 33 x 33 samples in 16-cell tiles, 513 x 513
//                samples in real 256-cell tiles, and a small global store (two roots, a child)
//                samples in real 256-cell tiles (2 x 2 tiles of 257 x 257 and their parent)
//   keyframes/   keyframe JSON files as tellus view records them, and edge cases
//   dem/         small rasters (GeoTIFF of several types with nodata, scale and georeferencing,
//                16-bit PNG, Terrain-RGB PNG, ASCII grid) behind the DEM target's two bytes
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
  m.sources = {{"seed.tif", {-180.0, -90.0, 180.0, 90.0}, 5.625, 1}};
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
  return writer.value()->finish(m).ok();
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
  return writer.value()->finishWithMetadata(globalMetadataToJson(m)).ok();
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

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_seed_corpus OUTPUT_FOLDER\n");
    return 2;
  }
  const fs::path root = argv[1];
  for (const char* folder : {"store", "keyframes", "dem"}) fs::create_directories(root / folder);
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
  return 0;
}
