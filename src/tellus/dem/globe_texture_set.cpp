#include "tellus/dem/globe_texture_set.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <vector>

#include <spdlog/spdlog.h>
#include <zstd.h>

#include "tellus/dem/gdal_support.hpp"

namespace tellus {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kEarthRadiusM = 6371000.0;
constexpr double kAltitudeTopM = 8848.0;  // the altitude map's 255
constexpr std::uint32_t kCacheVersion = 1;

struct CacheHeader {
  char magic[8] = {'T', 'L', 'S', 'C', 'U', 'B', 'E', '1'};
  std::uint32_t size = 0;
  std::uint32_t channels = 0;
  std::uint64_t signature = 0;
  std::uint64_t compressedBytes = 0;
};

// FNV-1a over the bytes of each value.
struct Signature {
  std::uint64_t hash = 1469598103934665603ull;
  template <typename T>
  void add(const T& value) {
    const auto* bytes = reinterpret_cast<const unsigned char*>(&value);
    for (std::size_t i = 0; i < sizeof(T); ++i) {
      hash = (hash ^ bytes[i]) * 1099511628211ull;
    }
  }
  void addFile(const std::filesystem::path& path) {
    std::error_code error;
    add(std::uint64_t(std::filesystem::file_size(path, error)));
    add(std::int64_t(std::filesystem::last_write_time(path, error).time_since_epoch().count()));
  }
};

std::optional<CubeMap> readCache(const std::filesystem::path& path, std::uint64_t signature) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  CacheHeader header;
  in.read(reinterpret_cast<char*>(&header), sizeof header);
  if (!in || std::memcmp(header.magic, CacheHeader{}.magic, 8) != 0 ||
      header.signature != signature || header.size == 0 || header.size > 16384 ||
      header.channels == 0 || header.channels > 4 || header.compressedBytes > (1ull << 34)) {
    return std::nullopt;
  }
  std::vector<char> compressed(header.compressedBytes);
  in.read(compressed.data(), std::streamsize(compressed.size()));
  if (!in) return std::nullopt;
  CubeMap cube;
  cube.size = int(header.size);
  cube.channels = int(header.channels);
  const std::size_t faceBytes = std::size_t(cube.size) * std::size_t(cube.size) * std::size_t(cube.channels);
  std::vector<std::uint8_t> all(6 * faceBytes);
  const std::size_t got = ZSTD_decompress(all.data(), all.size(), compressed.data(), compressed.size());
  if (ZSTD_isError(got) || got != all.size()) return std::nullopt;
  for (int f = 0; f < 6; ++f) {
    cube.faces[std::size_t(f)].assign(all.begin() + std::ptrdiff_t(f * faceBytes),
                                      all.begin() + std::ptrdiff_t((f + 1) * faceBytes));
  }
  return cube;
}

// Written to a temporary name and renamed: a reader never sees half a file.
void writeCache(const std::filesystem::path& path, const CubeMap& cube, std::uint64_t signature) {
  std::vector<std::uint8_t> all;
  for (const auto& face : cube.faces) all.insert(all.end(), face.begin(), face.end());
  std::vector<char> compressed(ZSTD_compressBound(all.size()));
  const std::size_t bytes = ZSTD_compress(compressed.data(), compressed.size(), all.data(), all.size(), 3);
  if (ZSTD_isError(bytes)) return;
  CacheHeader header;
  header.size = std::uint32_t(cube.size);
  header.channels = std::uint32_t(cube.channels);
  header.signature = signature;
  header.compressedBytes = bytes;
  std::error_code error;
  std::filesystem::create_directories(path.parent_path(), error);
  const std::filesystem::path temporary = path.string() + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(&header), sizeof header);
    out.write(compressed.data(), std::streamsize(bytes));
    if (!out) {
      spdlog::warn("could not write the cube-map cache '{}'", path.string());
      std::filesystem::remove(temporary, error);
      return;
    }
  }
  std::filesystem::rename(temporary, path, error);
  if (error) spdlog::warn("could not write the cube-map cache '{}': {}", path.string(), error.message());
}

// Interleaves single- and multi-band images into one of `channels` bands.
LatLonImage interleave(const std::vector<std::pair<const LatLonImage*, int>>& parts) {
  LatLonImage out;
  out.width = parts.front().first->width;
  out.height = parts.front().first->height;
  for (const auto& [image, count] : parts) out.channels += count;
  out.pixels.resize(std::size_t(out.width) * std::size_t(out.height) * std::size_t(out.channels));
  const std::size_t pixels = std::size_t(out.width) * std::size_t(out.height);
  int at = 0;
  for (const auto& [image, count] : parts) {
    for (std::size_t p = 0; p < pixels; ++p) {
      for (int c = 0; c < count; ++c) {
        out.pixels[p * std::size_t(out.channels) + std::size_t(at + c)] =
            image->pixels[p * std::size_t(image->channels) + std::size_t(c)];
      }
    }
    at += count;
  }
  return out;
}

}  // namespace

Result<LatLonImage> loadWholeGlobeImage(const std::filesystem::path& path, int channels) {
  gdal::ensureRegistered();
  const std::string name = path.string();
  Result<gdal::DatasetPtr> opened =
      gdal::openRasterFile(path, "globe image", "a whole-globe image such as the Blue Marble set's");
  if (!opened) return opened.error();
  gdal::DatasetPtr dataset = std::move(opened.value());
  if (dataset->GetRasterCount() < channels) {
    return makeError("globe image '{}' has {} band(s), {} needed", name, dataset->GetRasterCount(),
                     channels);
  }
  for (int b = 1; b <= channels; ++b) {
    if (dataset->GetRasterBand(b)->GetRasterDataType() != GDT_Byte) {
      return makeError("globe image '{}': band {} is not 8-bit", name, b);
    }
  }
  const int width = dataset->GetRasterXSize(), height = dataset->GetRasterYSize();
  double gt[6] = {};
  const bool georeferenced = dataset->GetGeoTransform(gt) == CE_None;
  const bool wholeGlobe =
      georeferenced ? std::abs(gt[0] + 180.0) < 1e-6 && std::abs(gt[3] - 90.0) < 1e-6 &&
                          std::abs(gt[1] * width - 360.0) < 1e-6 &&
                          std::abs(gt[5] * height + 180.0) < 1e-6 && gt[2] == 0.0 && gt[4] == 0.0
                    : width == 2 * height;
  if (!wholeGlobe || width < 8 || height < 4 || width > 65536) {
    return makeError("globe image '{}' ({} x {}) does not cover the whole globe in plate carree "
                     "(-180..180 E, 90..-90 N)",
                     name, width, height);
  }
  LatLonImage image;
  image.width = width;
  image.height = height;
  image.channels = channels;
  image.pixels.resize(std::size_t(width) * std::size_t(height) * std::size_t(channels));
  std::vector<int> bands(static_cast<std::size_t>(channels), 0);
  for (int b = 0; b < channels; ++b) bands[std::size_t(b)] = b + 1;
  if (dataset->RasterIO(GF_Read, 0, 0, width, height, image.pixels.data(), width, height, GDT_Byte,
                        channels, bands.data(), channels, std::int64_t(width) * channels, 1,
                        nullptr) != CE_None) {
    return makeError("globe image '{}': {}", name, gdal::lastError());
  }
  return image;
}

LatLonImage bumpMapFromAltitude(const LatLonImage& altitude, double bumpScale) {
  LatLonImage bump;
  bump.width = altitude.width;
  bump.height = altitude.height;
  bump.channels = 4;
  bump.pixels.resize(std::size_t(bump.width) * std::size_t(bump.height) * 4);
  const auto h = [&](int i, int j) {
    i = (i % altitude.width + altitude.width) % altitude.width;
    j = std::clamp(j, 0, altitude.height - 1);
    return double(altitude.pixels[(std::size_t(j) * std::size_t(altitude.width) + std::size_t(i)) *
                                  std::size_t(altitude.channels)]) *
           kAltitudeTopM / 255.0 * bumpScale;
  };
  const double northM = kPi * kEarthRadiusM / altitude.height;  // a row's height
  for (int j = 0; j < altitude.height; ++j) {
    const double lat = (90.0 - (j + 0.5) * 180.0 / altitude.height) * kPi / 180.0;
    const double eastM = std::max(2.0 * kPi * kEarthRadiusM * std::cos(lat) / altitude.width, 1.0);
    for (int i = 0; i < altitude.width; ++i) {
      const double dEast = (h(i + 1, j) - h(i - 1, j)) / (2.0 * eastM);
      const double dNorth = (h(i, j - 1) - h(i, j + 1)) / (2.0 * northM);
      const double length = std::sqrt(dEast * dEast + dNorth * dNorth + 1.0);
      // Weights of the normal, tangent (east) and binormal (north).
      const double weights[3] = {1.0 / length, -dEast / length, -dNorth / length};
      std::uint8_t* out = &bump.pixels[(std::size_t(j) * std::size_t(bump.width) + std::size_t(i)) * 4];
      for (int c = 0; c < 3; ++c) {
        out[c] = std::uint8_t(std::clamp(std::lround((weights[c] * 0.5 + 0.5) * 255.0), 0L, 255L));
      }
      out[3] = altitude.pixels[(std::size_t(j) * std::size_t(altitude.width) + std::size_t(i)) *
                               std::size_t(altitude.channels)];
    }
  }
  return bump;
}

Result<GlobeTextureSet> loadGlobeTextureSet(const std::filesystem::path& sourceDir,
                                            const std::filesystem::path& cacheDir,
                                            const GlobeTextureOptions& options) {
  if (options.faceSize < 16 || options.faceSize > 8192) {
    return makeError("cube-map faces must be 16 to 8192 texels, got {}", options.faceSize);
  }
  Signature signature;
  signature.add(kCacheVersion);
  signature.add(options.faceSize);
  signature.add(options.bumpScale);
  for (const char* file : {kBlueMarbleColour, kBlueMarbleAltitude, kBlueMarbleClouds,
                           kBlueMarbleNight, kBlueMarbleWater}) {
    if (!std::filesystem::is_regular_file(sourceDir / file)) {
      return makeError("the globe textures need '{}' in '{}' (NASA's Blue Marble set)", file,
                       sourceDir.string());
    }
    signature.addFile(sourceDir / file);
  }
  const auto cachePath = [&](const char* name) {
    return cacheDir / fmt::format("{}-{}.cube", name, options.faceSize);
  };
  GlobeTextureSet set;
  std::optional<CubeMap> surface = readCache(cachePath("surface"), signature.hash);
  std::optional<CubeMap> relief = readCache(cachePath("relief"), signature.hash);
  std::optional<CubeMap> sky = readCache(cachePath("sky"), signature.hash);
  if (surface && relief && sky) {
    spdlog::debug("globe textures from the cache '{}'", cacheDir.string());
    return GlobeTextureSet{std::move(*surface), std::move(*relief), std::move(*sky)};
  }
  spdlog::info("converting the Blue Marble set to {}-texel cube maps (once; cached in '{}')",
               options.faceSize, cacheDir.string());
  const auto load = [&](const char* file, int channels) {
    return loadWholeGlobeImage(sourceDir / file, channels);
  };
  Result<LatLonImage> colour = load(kBlueMarbleColour, 3);
  if (!colour) return colour.error();
  Result<LatLonImage> water = load(kBlueMarbleWater, 1);
  if (!water) return water.error();
  Result<LatLonImage> altitude = load(kBlueMarbleAltitude, 1);
  if (!altitude) return altitude.error();
  Result<LatLonImage> clouds = load(kBlueMarbleClouds, 1);
  if (!clouds) return clouds.error();
  Result<LatLonImage> night = load(kBlueMarbleNight, 1);
  if (!night) return night.error();
  for (const LatLonImage* image : {&water.value(), &altitude.value(), &clouds.value(), &night.value()}) {
    if (image->width != colour->width || image->height != colour->height) {
      return makeError("the Blue Marble images in '{}' differ in size ({} x {} and {} x {})",
                       sourceDir.string(), colour->width, colour->height, image->width,
                       image->height);
    }
  }
  set.surface = latLonToCubeMap(interleave({{&colour.value(), 3}, {&water.value(), 1}}), options.faceSize);
  const LatLonImage bump = bumpMapFromAltitude(altitude.value(), options.bumpScale);
  set.relief = latLonToCubeMap(bump, options.faceSize);
  set.sky = latLonToCubeMap(interleave({{&clouds.value(), 1}, {&night.value(), 1}}), options.faceSize);
  writeCache(cachePath("surface"), set.surface, signature.hash);
  writeCache(cachePath("relief"), set.relief, signature.hash);
  writeCache(cachePath("sky"), set.sky, signature.hash);
  return set;
}

std::filesystem::path findBlueMarbleSet() {
  std::vector<std::filesystem::path> candidates;
  if (const char* env = std::getenv("TELLUS_BLUE_MARBLE")) candidates.emplace_back(env);
  candidates.emplace_back("../shared/data/bluemarble8k-global");
  candidates.emplace_back("shared/data/bluemarble8k-global");
  for (const std::filesystem::path& dir : candidates) {
    std::error_code error;
    if (std::filesystem::is_regular_file(dir / kBlueMarbleColour, error)) return dir;
  }
  return {};
}

}  // namespace tellus
