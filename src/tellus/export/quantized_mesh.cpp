#include "tellus/export/quantized_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include <glm/geometric.hpp>

#include "tellus/core/geodesy.hpp"

namespace tellus {
namespace {

// Appends little-endian values (the machines Tellus runs on are little-endian).
class ByteWriter {
 public:
  template <typename T>
  void put(T value) {
    const auto* p = reinterpret_cast<const std::byte*>(&value);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  void padTo(std::size_t alignment) {
    while (bytes_.size() % alignment != 0) bytes_.push_back(std::byte{0});
  }
  std::vector<std::byte>& bytes() { return bytes_; }

 private:
  std::vector<std::byte> bytes_;
};

class ByteReader {
 public:
  ByteReader(std::span<const std::byte> bytes, std::string_view where)
      : bytes_(bytes), where_(where) {}
  template <typename T>
  bool get(T& value) {
    if (bytes_.size() - offset_ < sizeof(T)) return false;
    std::memcpy(&value, bytes_.data() + offset_, sizeof(T));
    offset_ += sizeof(T);
    return true;
  }
  bool skipTo(std::size_t alignment) {
    const std::size_t aligned = (offset_ + alignment - 1) / alignment * alignment;
    if (aligned > bytes_.size()) return false;
    offset_ = aligned;
    return true;
  }
  bool skip(std::size_t n) {
    if (bytes_.size() - offset_ < n) return false;
    offset_ += n;
    return true;
  }
  std::size_t remaining() const { return bytes_.size() - offset_; }
  std::size_t offset() const { return offset_; }
  Error truncated(std::string_view what) const {
    return makeError("{}: quantized-mesh tile truncated in its {} (byte {} of {})", where_, what,
                     offset_, bytes_.size());
  }

 private:
  std::span<const std::byte> bytes_;
  std::size_t offset_ = 0;
  std::string_view where_;
};

std::uint16_t zigZag(int value) {
  return std::uint16_t((value << 1) ^ (value >> 31));
}
int unZigZag(std::uint16_t value) {
  return int(value >> 1) ^ -int(value & 1);
}

void putDeltas(ByteWriter& out, const std::vector<std::uint16_t>& values) {
  int previous = 0;
  for (const std::uint16_t value : values) {
    out.put(zigZag(int(value) - previous));
    previous = value;
  }
}

template <typename Index>
void putIndexSections(ByteWriter& out, const QuantizedMeshTile& tile) {
  out.padTo(sizeof(Index));
  out.put(std::uint32_t(tile.indices.size() / 3));
  std::uint32_t highest = 0;
  for (const std::uint32_t index : tile.indices) {
    const std::uint32_t code = highest - index;
    out.put(Index(code));
    if (code == 0) ++highest;
  }
  for (const auto* edge : {&tile.westEdge, &tile.southEdge, &tile.eastEdge, &tile.northEdge}) {
    out.put(std::uint32_t(edge->size()));
    for (const std::uint32_t index : *edge) out.put(Index(index));
  }
}

template <typename Index>
Status getIndexSections(ByteReader& in, QuantizedMeshTile& tile, std::string_view where) {
  const std::size_t vertexCount = tile.u.size();
  if (!in.skipTo(sizeof(Index))) return in.truncated("index padding");
  std::uint32_t triangles = 0;
  if (!in.get(triangles)) return in.truncated("triangle count");
  if (std::uint64_t(triangles) * 3 * sizeof(Index) > in.remaining()) {
    return in.truncated("indices");
  }
  tile.indices.resize(std::size_t(triangles) * 3);
  std::uint32_t highest = 0;
  for (std::uint32_t& index : tile.indices) {
    Index code = 0;
    in.get(code);
    if (code > highest) {
      return makeError("{}: quantized-mesh index code {} above its high-water mark {}", where,
                       std::uint32_t(code), highest);
    }
    index = highest - code;
    if (code == 0) ++highest;
    if (index >= vertexCount) {
      return makeError("{}: quantized-mesh index {} out of range ({} vertices)", where, index,
                       vertexCount);
    }
  }
  for (auto* edge : {&tile.westEdge, &tile.southEdge, &tile.eastEdge, &tile.northEdge}) {
    std::uint32_t count = 0;
    if (!in.get(count)) return in.truncated("edge vertex count");
    if (std::uint64_t(count) * sizeof(Index) > in.remaining()) {
      return in.truncated("edge vertices");
    }
    edge->resize(count);
    for (std::uint32_t& index : *edge) {
      Index value = 0;
      in.get(value);
      if (value >= vertexCount) {
        return makeError("{}: quantized-mesh edge vertex {} out of range ({} vertices)", where,
                         std::uint32_t(value), vertexCount);
      }
      index = value;
    }
  }
  return {};
}

double signNotZero(double value) { return value < 0.0 ? -1.0 : 1.0; }

std::uint8_t toSnorm255(double value) {
  return std::uint8_t(std::lround((std::clamp(value, -1.0, 1.0) * 0.5 + 0.5) * 255.0));
}

// WGS84 semi-axes: the ellipsoid-scaled frame divides x and y by a and z by b.
glm::dvec3 toScaledSpace(const glm::dvec3& ecef) {
  return {ecef.x / wgs84::kSemiMajorAxisM, ecef.y / wgs84::kSemiMajorAxisM,
          ecef.z / wgs84::kSemiMinorAxisM};
}

}  // namespace

Result<std::vector<std::byte>> encodeQuantizedMesh(const QuantizedMeshTile& tile) {
  const std::size_t n = tile.u.size();
  if (tile.v.size() != n || tile.height.size() != n ||
      (!tile.octNormals.empty() && tile.octNormals.size() != n)) {
    return makeError("quantized-mesh tile: per-vertex arrays of different sizes");
  }
  if (!tile.waterMask.empty() && tile.waterMask.size() != 1 &&
      tile.waterMask.size() != kQuantizedMeshWaterMaskSide * kQuantizedMeshWaterMaskSide) {
    return makeError("quantized-mesh tile: a water mask of {} bytes (1 or 65536)", tile.waterMask.size());
  }
  if (n > std::size_t(std::numeric_limits<std::uint32_t>::max()) || tile.indices.size() % 3 != 0) {
    return makeError("quantized-mesh tile: {} vertices and {} indices", n, tile.indices.size());
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (tile.u[i] > kQuantizedMeshMaxCoordinate || tile.v[i] > kQuantizedMeshMaxCoordinate ||
        tile.height[i] > kQuantizedMeshMaxCoordinate) {
      return makeError("quantized-mesh tile: vertex {} has a coordinate over {}", i,
                       kQuantizedMeshMaxCoordinate);
    }
  }
  std::uint32_t highest = 0;
  for (const std::uint32_t index : tile.indices) {
    if (index > highest || index >= n) {
      return makeError(
          "quantized-mesh tile: index {} breaks first-use order or range (next new vertex {})",
          index, highest);
    }
    if (index == highest) ++highest;
  }
  for (const auto* edge : {&tile.westEdge, &tile.southEdge, &tile.eastEdge, &tile.northEdge}) {
    for (const std::uint32_t index : *edge) {
      if (index >= n) return makeError("quantized-mesh tile: edge vertex {} out of range", index);
    }
  }

  ByteWriter out;
  const QuantizedMeshHeader& h = tile.header;
  for (const double value : {h.centreEcef.x, h.centreEcef.y, h.centreEcef.z}) out.put(value);
  out.put(h.minHeightM);
  out.put(h.maxHeightM);
  for (const double value : {h.boundingSphereCentreEcef.x, h.boundingSphereCentreEcef.y,
                             h.boundingSphereCentreEcef.z, h.boundingSphereRadiusM,
                             h.horizonOcclusionPoint.x, h.horizonOcclusionPoint.y,
                             h.horizonOcclusionPoint.z}) {
    out.put(value);
  }
  out.put(std::uint32_t(n));
  putDeltas(out, tile.u);
  putDeltas(out, tile.v);
  putDeltas(out, tile.height);
  if (n > 65536) {
    putIndexSections<std::uint32_t>(out, tile);
  } else {
    putIndexSections<std::uint16_t>(out, tile);
  }
  if (!tile.octNormals.empty()) {
    out.put(kQuantizedMeshOctNormalsExtension);
    out.put(std::uint32_t(2 * n));
    for (const auto& normal : tile.octNormals) {
      out.put(normal[0]);
      out.put(normal[1]);
    }
  }
  if (!tile.waterMask.empty()) {
    out.put(kQuantizedMeshWaterMaskExtension);
    out.put(std::uint32_t(tile.waterMask.size()));
    for (const std::uint8_t value : tile.waterMask) out.put(value);
  }
  if (!tile.metadataJson.empty()) {
    out.put(kQuantizedMeshMetadataExtension);
    out.put(std::uint32_t(4 + tile.metadataJson.size()));
    out.put(std::uint32_t(tile.metadataJson.size()));
    for (const char c : tile.metadataJson) out.put(std::uint8_t(c));
  }
  return std::move(out.bytes());
}

Result<QuantizedMeshTile> decodeQuantizedMesh(std::span<const std::byte> bytes,
                                              std::string_view where) {
  ByteReader in(bytes, where);
  QuantizedMeshTile tile;
  QuantizedMeshHeader& h = tile.header;
  double doubles[3];
  for (double& value : doubles) {
    if (!in.get(value)) return in.truncated("header");
  }
  h.centreEcef = {doubles[0], doubles[1], doubles[2]};
  if (!in.get(h.minHeightM) || !in.get(h.maxHeightM)) return in.truncated("header");
  double rest[7];
  for (double& value : rest) {
    if (!in.get(value)) return in.truncated("header");
  }
  h.boundingSphereCentreEcef = {rest[0], rest[1], rest[2]};
  h.boundingSphereRadiusM = rest[3];
  h.horizonOcclusionPoint = {rest[4], rest[5], rest[6]};

  std::uint32_t n = 0;
  if (!in.get(n)) return in.truncated("vertex count");
  if (std::uint64_t(n) * 6 > in.remaining()) return in.truncated("vertices");
  for (auto* values : {&tile.u, &tile.v, &tile.height}) {
    values->resize(n);
    int value = 0;
    for (std::uint16_t& out : *values) {
      std::uint16_t code = 0;
      in.get(code);
      value += unZigZag(code);
      if (value < 0 || value > kQuantizedMeshMaxCoordinate) {
        return makeError("{}: quantized-mesh vertex coordinate {} outside 0..{}", where, value,
                         kQuantizedMeshMaxCoordinate);
      }
      out = std::uint16_t(value);
    }
  }
  if (Status s = n > 65536 ? getIndexSections<std::uint32_t>(in, tile, where)
                           : getIndexSections<std::uint16_t>(in, tile, where);
      !s) {
    return s.error();
  }
  while (in.remaining() > 0) {
    std::uint8_t id = 0;
    std::uint32_t length = 0;
    if (!in.get(id) || !in.get(length)) return in.truncated("extension header");
    if (length > in.remaining()) return in.truncated("extension");
    if (id == kQuantizedMeshOctNormalsExtension) {
      if (length != 2 * std::uint64_t(n)) {
        return makeError("{}: oct-normal extension of {} bytes for {} vertices", where, length,
                         n);
      }
      tile.octNormals.resize(n);
      for (auto& normal : tile.octNormals) {
        in.get(normal[0]);
        in.get(normal[1]);
      }
    } else if (id == kQuantizedMeshWaterMaskExtension) {
      if (length != 1 && length != kQuantizedMeshWaterMaskSide * kQuantizedMeshWaterMaskSide) {
        return makeError("{}: water mask extension of {} bytes (1 or 65536)", where, length);
      }
      tile.waterMask.resize(length);
      for (std::uint8_t& value : tile.waterMask) in.get(value);
    } else if (id == kQuantizedMeshMetadataExtension) {
      std::uint32_t textLength = 0;
      if (length < 4 || !in.get(textLength) || textLength > length - 4) {
        return makeError("{}: metadata extension of {} bytes holds no JSON text of its stated length",
                         where, length);
      }
      tile.metadataJson.resize(textLength);
      for (char& c : tile.metadataJson) {
        std::uint8_t value = 0;
        in.get(value);
        c = char(value);
      }
      in.skip(length - 4 - textLength);
    } else {
      in.skip(length);
    }
  }
  return tile;
}

std::array<std::uint8_t, 2> octEncodeNormal(const glm::dvec3& unit) {
  const double l1 = std::abs(unit.x) + std::abs(unit.y) + std::abs(unit.z);
  double x = unit.x / l1, y = unit.y / l1;
  if (unit.z < 0.0) {
    const double oldX = x;
    x = (1.0 - std::abs(y)) * signNotZero(oldX);
    y = (1.0 - std::abs(oldX)) * signNotZero(y);
  }
  return {toSnorm255(x), toSnorm255(y)};
}

glm::dvec3 octDecodeNormal(std::array<std::uint8_t, 2> encoded) {
  double x = double(encoded[0]) / 255.0 * 2.0 - 1.0;
  double y = double(encoded[1]) / 255.0 * 2.0 - 1.0;
  const double z = 1.0 - (std::abs(x) + std::abs(y));
  if (z < 0.0) {
    const double oldX = x;
    x = (1.0 - std::abs(y)) * signNotZero(oldX);
    y = (1.0 - std::abs(oldX)) * signNotZero(y);
  }
  return glm::normalize(glm::dvec3(x, y, z));
}

bool horizonOcclusionPoint(const glm::dvec3& directionEcef, std::span<const glm::dvec3> pointsEcef,
                           glm::dvec3& point) {
  const glm::dvec3 direction = glm::normalize(toScaledSpace(directionEcef));
  double magnitude = 0.0;
  for (const glm::dvec3& ecef : pointsEcef) {
    const glm::dvec3 scaled = toScaledSpace(ecef);
    const double length = glm::length(scaled);
    const glm::dvec3 toPoint = scaled / length;
    const double clampedSquared = std::max(1.0, length * length);
    const double clamped = std::max(1.0, length);
    const double cosAlpha = glm::dot(toPoint, direction);
    const double sinAlpha = glm::length(glm::cross(toPoint, direction));
    const double cosBeta = 1.0 / clamped;
    const double sinBeta = std::sqrt(clampedSquared - 1.0) * cosBeta;
    const double denominator = cosAlpha * cosBeta - sinAlpha * sinBeta;
    if (denominator <= 0.0) return false;
    magnitude = std::max(magnitude, 1.0 / denominator);
  }
  point = direction * magnitude;
  return true;
}

}  // namespace tellus
