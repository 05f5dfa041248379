#include "tellus/formats/stacks/stack_file.hpp"

#include <cstring>
#include <fstream>

#include <xxhash.h>
#include <zstd.h>

#include "tellus/core/atomic_output.hpp"
#include "tellus/core/byte_fields.hpp"
#include "tellus/core/geotransform_check.hpp"
#include "tellus/core/input_file.hpp"
#include "tellus/core/memory_budget.hpp"
#include "tellus/dem/georeference_check.hpp"
#include "tellus/formats/stacks/stack_aggregation.hpp"
#include "tellus/tiles/store_checksums.hpp"

namespace tellus {
namespace {

constexpr char kMagic[8] = {'T', 'L', 'S', 'S', 'T', 'K', '0', '1'};
constexpr std::uint32_t kVersionPlain = 1, kVersionGeoReferenced = 2;
constexpr std::size_t kHeaderBytes = 64, kLevelBytes = 48, kLayerBytes = 9;
constexpr std::size_t kGeoFixedBytes = 48 + 12;                 // geotransform, flags, two lengths
constexpr std::uint64_t kMaxGeoBytes = std::uint64_t(1) << 20;  // WKT is a few KiB
constexpr std::uint32_t kHasGeoTransform = 1, kGeographic = 2;
constexpr int kMaxLevels = 32;
constexpr std::uint64_t kMaxFileBytes = std::uint64_t(16) << 30;
constexpr double kMaxZstdRatio = 32768.0;

std::vector<std::byte> rawBlock(const StackTerrain& level) {
  const auto& offsets = level.offsets();
  const auto& layers = level.layers();
  std::vector<std::byte> raw(offsets.size() * 4 + layers.size() * kLayerBytes);
  std::memcpy(raw.data(), offsets.data(), offsets.size() * 4);
  std::size_t at = offsets.size() * 4;
  for (const StackLayer& l : layers) {
    std::memcpy(raw.data() + at, &l.bottomM, 4);
    std::memcpy(raw.data() + at + 4, &l.topM, 4);
    raw[at + 8] = std::byte(l.material);
    at += kLayerBytes;
  }
  return raw;
}

std::vector<std::byte> georeferenceBlock(const GeoReference& georef) {
  std::vector<std::byte> out(kGeoFixedBytes + georef.crsWkt.size() + georef.crsName.size());
  for (int i = 0; i < 6; ++i) putField<double>(out, std::size_t(8 * i), georef.geoTransform[std::size_t(i)]);
  putField<std::uint32_t>(out, 48, (georef.hasGeoTransform ? kHasGeoTransform : 0u) |
                                       (georef.isGeographic ? kGeographic : 0u));
  putField<std::uint32_t>(out, 52, std::uint32_t(georef.crsWkt.size()));
  putField<std::uint32_t>(out, 56, std::uint32_t(georef.crsName.size()));
  std::memcpy(out.data() + kGeoFixedBytes, georef.crsWkt.data(), georef.crsWkt.size());
  std::memcpy(out.data() + kGeoFixedBytes + georef.crsWkt.size(), georef.crsName.data(), georef.crsName.size());
  return out;
}

// The header, the level table and the georeference of a stack file, checked.
struct StackHead {
  std::uint32_t levelCount = 0;
  double spacingM = 0.0;
  GeoReference georef;
  std::uint64_t blocksStart = 0;  // where level 0's block must start
};

// Reads and checks the head of `in`, a file of `size` bytes named `name`: magic, version,
// level count, the checksum over header, table and georeference, the spacing, and the
// georeference (checkGeoReference on level 0's size).
Result<StackHead> readHead(std::istream& in, std::uint64_t size, const std::string& name) {
  std::vector<std::byte> head(kHeaderBytes);
  if (size < kHeaderBytes || !in.read(reinterpret_cast<char*>(head.data()), std::streamsize(kHeaderBytes)) ||
      std::memcmp(head.data(), kMagic, sizeof(kMagic)) != 0) {
    return makeError("'{}' is not a Tellus stack file (.tstack)", name);
  }
  const std::uint32_t version = getField<std::uint32_t>(head, 8);
  if (version != kVersionPlain && version != kVersionGeoReferenced) {
    return makeError("'{}': stack file version {} (this Tellus reads {} and {})", name, version,
                     kVersionPlain, kVersionGeoReferenced);
  }
  StackHead h;
  h.levelCount = getField<std::uint32_t>(head, 12);
  h.spacingM = getField<double>(head, 16);
  const std::uint64_t geoBytes = getField<std::uint64_t>(head, 32);
  if (h.levelCount < 1 || h.levelCount > kMaxLevels || size < kHeaderBytes + kLevelBytes * h.levelCount) {
    return makeError("'{}': a header of {} levels in {} bytes", name, h.levelCount, size);
  }
  if ((version == kVersionPlain && geoBytes != 0) ||
      (version == kVersionGeoReferenced && (geoBytes < kGeoFixedBytes || geoBytes > kMaxGeoBytes)) ||
      geoBytes > size - kHeaderBytes - kLevelBytes * h.levelCount) {
    return makeError("'{}': a georeference of {} bytes in a version {} file of {} bytes (corrupt)", name,
                     geoBytes, version, size);
  }
  h.blocksStart = kHeaderBytes + kLevelBytes * h.levelCount + geoBytes;
  head.resize(h.blocksStart);
  if (!in.read(reinterpret_cast<char*>(head.data() + kHeaderBytes), std::streamsize(h.blocksStart - kHeaderBytes))) {
    return makeError("cannot read '{}'", name);
  }
  std::vector<std::byte> checked(head);
  std::memset(checked.data() + 56, 0, 8);
  if (!store_format::checksumMatches(XXH64(checked.data(), checked.size(), 0), getField<std::uint64_t>(head, 56))) {
    return makeError("'{}': the header's checksum does not match (corrupt)", name);
  }
  if (Status spacingOk = checkSampleSpacing(h.spacingM, h.spacingM); !spacingOk) {
    return makeError("'{}': {}", name, spacingOk.error().message);
  }
  if (geoBytes == 0) return h;
  const std::size_t at = kHeaderBytes + kLevelBytes * h.levelCount;
  const std::vector<std::byte> geo(head.begin() + std::ptrdiff_t(at), head.end());
  for (int i = 0; i < 6; ++i) h.georef.geoTransform[std::size_t(i)] = getField<double>(geo, std::size_t(8 * i));
  const auto flags = getField<std::uint32_t>(geo, 48);
  const std::uint64_t wktBytes = getField<std::uint32_t>(geo, 52), nameBytes = getField<std::uint32_t>(geo, 56);
  if (flags > (kHasGeoTransform | kGeographic) || kGeoFixedBytes + wktBytes + nameBytes != geoBytes) {
    return makeError("'{}': its georeference is corrupt (flags {}, {} + {} bytes of CRS in {})", name, flags,
                     wktBytes, nameBytes, geoBytes - kGeoFixedBytes);
  }
  h.georef.hasGeoTransform = (flags & kHasGeoTransform) != 0;
  h.georef.isGeographic = (flags & kGeographic) != 0;
  const char* text = reinterpret_cast<const char*>(geo.data() + kGeoFixedBytes);
  h.georef.crsWkt.assign(text, wktBytes);
  h.georef.crsName.assign(text + wktBytes, nameBytes);
  const auto width = getField<std::uint32_t>(head, kHeaderBytes), height = getField<std::uint32_t>(head, kHeaderBytes + 4);
  if (width < 1 || height < 1 || width > (1u << 20) || height > (1u << 20)) {
    return makeError("'{}': level 0 is {} x {} stacks: not a pyramid", name, width, height);
  }
  if (Status valid = checkGeoReference(h.georef, int(width), int(height)); !valid) {
    return makeError("'{}': its georeference: {}", name, valid.error().message);
  }
  return h;
}

}  // namespace

bool hasStackGeoReference(const GeoReference& georef) {
  return georef.hasGeoTransform || !georef.crsWkt.empty();
}

Status writeStackFile(const std::filesystem::path& path, const std::vector<StackTerrain>& levels,
                      const GeoReference& georef) {
  if (levels.empty() || int(levels.size()) > kMaxLevels) {
    return makeError("a stack file holds 1 to {} levels, not {}", kMaxLevels, levels.size());
  }
  if (Status geometry = checkStackGeometry(levels.front().spacingM(), levels.front().topM()); !geometry) {
    return makeError("cannot write '{}': {}", path.string(), geometry.error().message);
  }
  for (std::size_t k = 1; k < levels.size(); ++k) {
    if (levels[k].width() != (levels[k - 1].width() + 1) / 2 ||
        levels[k].height() != (levels[k - 1].height() + 1) / 2) {
      return makeError("stack level {} is {} x {}, not half of level {}", k, levels[k].width(),
                       levels[k].height(), k - 1);
    }
  }
  std::vector<std::byte> geo;
  if (hasStackGeoReference(georef)) {
    if (Status valid = checkGeoReference(georef, levels.front().width(), levels.front().height()); !valid) {
      return makeError("cannot write '{}' with its georeference: {}", path.string(), valid.error().message);
    }
    geo = georeferenceBlock(georef);
  }
  std::vector<std::byte> head(kHeaderBytes + kLevelBytes * levels.size());
  std::memcpy(head.data(), kMagic, sizeof(kMagic));
  putField<std::uint32_t>(head, 8, geo.empty() ? kVersionPlain : kVersionGeoReferenced);
  putField<std::uint32_t>(head, 12, std::uint32_t(levels.size()));
  putField<double>(head, 16, levels.front().spacingM());
  putField<std::uint64_t>(head, 32, geo.size());
  std::vector<std::vector<std::byte>> blocks;
  std::uint64_t offset = head.size() + geo.size();
  for (std::size_t k = 0; k < levels.size(); ++k) {
    const std::vector<std::byte> raw = rawBlock(levels[k]);
    std::vector<std::byte> packed(ZSTD_compressBound(raw.size()));
    const std::size_t size = ZSTD_compress(packed.data(), packed.size(), raw.data(), raw.size(), 9);
    if (ZSTD_isError(size)) return makeError("compressing stack level {}: {}", k, ZSTD_getErrorName(size));
    packed.resize(size);
    const std::size_t at = kHeaderBytes + kLevelBytes * k;
    putField<std::uint32_t>(head, at, std::uint32_t(levels[k].width()));
    putField<std::uint32_t>(head, at + 4, std::uint32_t(levels[k].height()));
    putField<std::uint64_t>(head, at + 8, levels[k].layerCount());
    putField<std::uint64_t>(head, at + 16, offset);
    putField<std::uint64_t>(head, at + 24, packed.size());
    putField<std::uint64_t>(head, at + 32, XXH64(raw.data(), raw.size(), 0));
    offset += packed.size();
    blocks.push_back(std::move(packed));
  }
  head.insert(head.end(), geo.begin(), geo.end());
  std::vector<std::byte> checked(head);
  std::memset(checked.data() + 56, 0, 8);
  putField<std::uint64_t>(head, 56, XXH64(checked.data(), checked.size(), 0));
  std::vector<std::byte> file = head;
  for (const auto& b : blocks) file.insert(file.end(), b.begin(), b.end());
  return writeBytesAtomically(path, file);
}

Status checkStackGeometry(double spacingM, float topM) {
  if (Status spacing = checkSampleSpacing(spacingM, spacingM); !spacing) return spacing;
  if (!(double(topM) / spacingM < kMaxStackHeightInSpacings)) {
    return makeError("its terrain is {} m tall at {:.3g} m between stacks: more than {} stack "
                     "spacings, which no density grid holds (rebuild it with a coarser --spacing)",
                     topM, spacingM, kMaxStackHeightInSpacings);
  }
  return {};
}

Result<std::vector<StackTerrain>> readStackFile(const std::filesystem::path& path,
                                                GeoReference* georef) {
  const std::string name = path.string();
  if (Status s = checkRegularInput(path); !s) return s.error();
  std::error_code ec;
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (ec || size > kMaxFileBytes) return makeError("'{}': cannot read its size, or larger than 16 GiB", name);
  if (Status memory = checkMemoryFor(fmt::format("reading '{}'", name), double(size),
                                     "free memory or set TELLUS_MEMORY_LIMIT_MB higher");
      !memory) {
    return memory.error();
  }
  std::ifstream in(path, std::ios::binary);
  Result<StackHead> head = readHead(in, size, name);
  if (!head) return head.error();
  const std::uint32_t levelCount = head->levelCount;
  const double spacing = head->spacingM;
  std::vector<std::byte> file(size);
  in.seekg(0);
  if (!in.read(reinterpret_cast<char*>(file.data()), std::streamsize(size))) {
    return makeError("cannot read '{}'", name);
  }
  std::vector<StackTerrain> levels;
  std::uint64_t expectedOffset = head->blocksStart;  // blocks follow the table and georeference
  for (std::uint32_t k = 0; k < levelCount; ++k) {
    const std::size_t at = kHeaderBytes + kLevelBytes * k;
    const auto width = getField<std::uint32_t>(file, at), height = getField<std::uint32_t>(file, at + 4);
    const auto layers = getField<std::uint64_t>(file, at + 8), offset = getField<std::uint64_t>(file, at + 16);
    const auto bytes = getField<std::uint64_t>(file, at + 24), checksum = getField<std::uint64_t>(file, at + 32);
    if (width < 1 || height < 1 || width > (1u << 20) || height > (1u << 20) ||
        (k > 0 && (width != (std::uint32_t(levels.back().width()) + 1) / 2 ||
                   height != (std::uint32_t(levels.back().height()) + 1) / 2))) {
      return makeError("'{}': level {} is {} x {} stacks: not a pyramid", name, k, width, height);
    }
    if (offset > size || bytes > size - offset || layers > (std::uint64_t(1) << 31)) {
      return makeError("'{}': level {}'s block lies beyond the file (truncated?)", name, k);
    }
    if (offset != expectedOffset) {
      return makeError("'{}': level {}'s block starts at byte {}, not {} where the previous one "
                       "ends (a corrupt table)",
                       name, k, offset, expectedOffset);
    }
    expectedOffset = offset + bytes;
    const std::uint64_t columns = std::uint64_t(width) * height;
    const std::uint64_t rawBytes = (columns + 1) * 4 + layers * kLayerBytes;
    const unsigned long long frame = ZSTD_getFrameContentSize(file.data() + offset, bytes);
    if (frame != rawBytes) {
      return makeError("'{}': level {}'s block does not hold its {} columns and {} layers", name, k,
                       columns, layers);
    }
    // No zstd frame expands more than kMaxZstdRatio times (a 4-byte RLE block gives 128 KiB):
    // a small block that declares gigabytes is corrupt, refused before anything is allocated.
    if (double(rawBytes) > double(bytes) * kMaxZstdRatio + 1024.0) {
      return makeError("'{}': level {}'s block of {} bytes declares {} of columns and layers, "
                       "more than zstd can expand it to (corrupt)",
                       name, k, bytes, formatByteCount(double(rawBytes)));
    }
    // The raw block, then the offsets and layers made from it.
    if (Status memory = checkMemoryFor(fmt::format("reading level {} of '{}'", k, name),
                                       2.0 * double(rawBytes) + double(layers) * sizeof(StackLayer),
                                       "free memory or set TELLUS_MEMORY_LIMIT_MB higher");
        !memory) {
      return memory.error();
    }
    std::vector<std::byte> raw(rawBytes);
    const std::size_t got = ZSTD_decompress(raw.data(), raw.size(), file.data() + offset, bytes);
    if (ZSTD_isError(got) || got != rawBytes ||
        !store_format::checksumMatches(XXH64(raw.data(), raw.size(), 0), checksum)) {
      return makeError("'{}': level {}'s block is corrupt (checksum)", name, k);
    }
    std::vector<std::uint32_t> offsets(columns + 1);
    std::memcpy(offsets.data(), raw.data(), offsets.size() * 4);
    std::vector<StackLayer> stackLayers(layers);
    std::size_t p = offsets.size() * 4;
    for (StackLayer& l : stackLayers) {
      std::memcpy(&l.bottomM, raw.data() + p, 4);
      std::memcpy(&l.topM, raw.data() + p + 4, 4);
      l.material = StackMaterial(raw[p + 8]);
      p += kLayerBytes;
    }
    Result<StackTerrain> level = StackTerrain::fromArrays(int(width), int(height), spacing * double(1u << k),
                                                          std::move(offsets), std::move(stackLayers));
    if (!level) return makeError("'{}': level {}: {}", name, k, level.error().message);
    levels.push_back(std::move(level.value()));
  }
  if (expectedOffset != size) {
    return makeError("'{}': {} bytes follow the last level's block (the file is {} bytes, its "
                     "levels end at {}): not a file Tellus wrote",
                     name, size - expectedOffset, size, expectedOffset);
  }
  if (Status geometry = checkStackGeometry(levels.front().spacingM(), levels.front().topM()); !geometry) {
    return makeError("'{}': {}", name, geometry.error().message);
  }
  if (georef != nullptr) *georef = std::move(head->georef);
  return levels;
}

Result<GeoReference> readStackGeoReference(const std::filesystem::path& path) {
  const std::string name = path.string();
  if (Status s = checkRegularInput(path); !s) return s.error();
  std::error_code ec;
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) return makeError("'{}': cannot read its size", name);
  std::ifstream in(path, std::ios::binary);
  Result<StackHead> head = readHead(in, size, name);
  if (!head) return head.error();
  return std::move(head->georef);
}

Status verifyStackPyramid(const std::vector<StackTerrain>& levels) {
  for (std::size_t k = 0; k + 1 < levels.size(); ++k) {
    Result<StackTerrain> aggregate = tryAggregateStackTerrain(levels[k]);
    if (!aggregate) return makeError("level {} cannot be aggregated: {}", k, aggregate.error().message);
    const StackTerrain& expected = aggregate.value();
    const StackTerrain& stored = levels[k + 1];
    if (expected.offsets() != stored.offsets()) {
      return makeError("level {} is not the aggregation of level {}: its columns hold other layer "
                       "counts",
                       k + 1, k);
    }
    const auto& a = expected.layers();
    const auto& b = stored.layers();
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (a[i].bottomM != b[i].bottomM || a[i].topM != b[i].topM || a[i].material != b[i].material) {
        return makeError("level {} is not the aggregation of level {}: layer {} is {}..{} m of "
                         "material {}, the aggregation gives {}..{} m of material {}",
                         k + 1, k, i, b[i].bottomM, b[i].topM, int(b[i].material), a[i].bottomM,
                         a[i].topM, int(a[i].material));
      }
    }
  }
  return {};
}

Result<StackFileSummary> summariseStackFile(const std::filesystem::path& path) {
  StackFileSummary s;
  Result<std::vector<StackTerrain>> levels = readStackFile(path, &s.georef);
  if (!levels) return levels.error();
  s.levels = int(levels->size());
  s.width = levels->front().width();
  s.height = levels->front().height();
  s.spacingM = levels->front().spacingM();
  std::error_code ec;
  s.fileBytes = std::filesystem::file_size(path, ec);
  for (const StackTerrain& t : *levels) {
    s.layers += t.layerCount();
    s.memoryBytes += t.bytes();
  }
  return s;
}

}  // namespace tellus
