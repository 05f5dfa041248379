#include "tellus/formats/bdam/bdam_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <utility>

#include <glm/common.hpp>
#include <xxhash.h>

#include "tellus/core/atomic_output.hpp"
#include "tellus/core/byte_fields.hpp"
#include "tellus/tiles/store_checksums.hpp"

namespace tellus::bdam {
namespace {

constexpr char kMagic[8] = {'T', 'B', 'D', 'A', 'M', 'v', '2', '\0'};
constexpr char kMagicVersion1[8] = {'T', 'B', 'D', 'A', 'M', 'v', '1', '\0'};
constexpr std::size_t kHeaderBytes = 64;
constexpr std::size_t kHeaderChecksumAt = 52;  // xxh64 of the header's bytes before it
constexpr std::size_t kEntryBytes = 56;

bool finite(float v) { return std::isfinite(v); }

}  // namespace

std::filesystem::path defaultPatchFilePath(const std::filesystem::path& input) {
  std::filesystem::path out = input;
  out.replace_extension(".bdam");
  return out;
}

Result<std::uint64_t> writePatchFile(const Hierarchy& h, const std::filesystem::path& path) {
  std::vector<std::byte> table(h.patches.size() * kEntryBytes);
  std::vector<std::byte> data;
  const std::uint64_t dataStart = kHeaderBytes + table.size();
  for (std::size_t i = 0; i < h.patches.size(); ++i) {
    const Patch& p = h.patches[i];
    glm::ivec2 origin = p.positions.empty() ? glm::ivec2(0) : p.positions.front();
    for (const glm::ivec2& q : p.positions) origin = glm::min(origin, q);
    const std::size_t start = data.size();
    for (std::size_t v = 0; v < p.positions.size(); ++v) {
      const glm::ivec2 d = p.positions[v] - origin;
      if (d.x > 0xffff || d.y > 0xffff) return makeError("BDAM patch {} spans more than 65535 samples", p.node);
      PackedVertex packed{std::uint16_t(d.x), std::uint16_t(d.y), p.heights[v]};
      const auto* bytes = reinterpret_cast<const std::byte*>(&packed);
      data.insert(data.end(), bytes, bytes + sizeof(packed));
    }
    const auto* indexBytes = reinterpret_cast<const std::byte*>(p.indices.data());
    data.insert(data.end(), indexBytes, indexBytes + p.indices.size() * sizeof(std::uint16_t));
    const std::size_t at = i * kEntryBytes;
    putField<std::uint64_t>(table, at + 0, p.node);
    putField<std::uint64_t>(table, at + 8, dataStart + start);
    putField<std::uint32_t>(table, at + 16, std::uint32_t(data.size() - start));
    putField<std::uint32_t>(table, at + 20, std::uint32_t(p.positions.size()));
    putField<std::uint32_t>(table, at + 24, std::uint32_t(p.indices.size()));
    putField<float>(table, at + 28, p.errorM);
    putField<float>(table, at + 32, p.minZ);
    putField<float>(table, at + 36, p.maxZ);
    putField<std::uint32_t>(table, at + 40, std::uint32_t(origin.x));
    putField<std::uint32_t>(table, at + 44, std::uint32_t(origin.y));
    putField<std::uint64_t>(table, at + 48, XXH64(data.data() + start, data.size() - start, 0));
  }
  std::vector<std::byte> header(kHeaderBytes, std::byte{0});
  std::memcpy(header.data(), kMagic, sizeof(kMagic));
  putField<std::uint32_t>(header, 8, std::uint32_t(h.gridWidth));
  putField<std::uint32_t>(header, 12, std::uint32_t(h.gridHeight));
  putField<std::uint32_t>(header, 16, std::uint32_t(h.domainLog2));
  putField<std::uint32_t>(header, 20, std::uint32_t(h.leafLevel));
  putField<std::uint32_t>(header, 24, std::uint32_t(h.patches.size()));
  putField<double>(header, 28, h.spacingXM);
  putField<double>(header, 36, h.spacingYM);
  putField<std::uint64_t>(header, 44, XXH64(table.data(), table.size(), 0));
  putField<std::uint64_t>(header, kHeaderChecksumAt, XXH64(header.data(), kHeaderChecksumAt, 0));
  std::vector<std::byte> file;
  file.reserve(header.size() + table.size() + data.size());
  for (const auto* block : {&header, &table, &data}) file.insert(file.end(), block->begin(), block->end());
  // Through a temporary renamed into place (never over an input, never half written); a full
  // disk or a refused destination is an error naming the file and the reason.
  if (Status written = writeBytesAtomically(path, file); !written) {
    return makeError("BDAM patch file: {}", written.error().message);
  }
  return std::uint64_t(file.size());
}

Result<PatchFile> PatchFile::open(const std::filesystem::path& path) {
  PatchFile f;
  f.path_ = path;
  f.fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (f.fd_ < 0) return makeError("cannot open BDAM patch file {}: {}", path.string(), std::strerror(errno));
  std::error_code ec;
  f.fileBytes_ = std::filesystem::file_size(path, ec);
  std::vector<std::byte> header(kHeaderBytes);
  const bool headerRead = !ec && f.fileBytes_ >= kHeaderBytes &&
                          ::pread(f.fd_, header.data(), kHeaderBytes, 0) == ssize_t(kHeaderBytes);
  if (headerRead && std::memcmp(header.data(), kMagicVersion1, sizeof(kMagicVersion1)) == 0) {
    return makeError("BDAM patch file {} was written by an older Tellus (format 1, no header "
                     "checksum): rebuild it with 'tellus build DEM... -o NAME.tstore --bdam'",
                     path.string());
  }
  if (!headerRead || std::memcmp(header.data(), kMagic, sizeof(kMagic)) != 0) {
    return makeError("{} is not a BDAM patch file (make one with 'tellus build DEM... -o NAME.tstore --bdam')",
                     path.string());
  }
  if (store_format::checksumMatches(XXH64(header.data(), kHeaderChecksumAt, 0),
                                    getField<std::uint64_t>(header, kHeaderChecksumAt)) == false) {
    return makeError("BDAM patch file {}: its header fails its checksum (corrupt file)", path.string());
  }
  // Checked as read (unsigned) before any becomes an int.
  const std::uint32_t width = getField<std::uint32_t>(header, 8), height = getField<std::uint32_t>(header, 12);
  const std::uint32_t domainLog2 = getField<std::uint32_t>(header, 16), leafLevel = getField<std::uint32_t>(header, 20);
  const std::uint32_t count = getField<std::uint32_t>(header, 24);
  f.spacingX_ = getField<double>(header, 28);
  f.spacingY_ = getField<double>(header, 36);
  if (width < 2 || height < 2 || width > kMaxGridSide || height > kMaxGridSide || domainLog2 > 16 ||
      leafLevel > 2 * domainLog2 || std::uint64_t(count) * kEntryBytes + kHeaderBytes > f.fileBytes_ ||
      !(f.spacingX_ > 0.0) || !(f.spacingY_ > 0.0) || !std::isfinite(f.spacingX_) || !std::isfinite(f.spacingY_)) {
    return makeError("BDAM patch file {}: its header is corrupt", path.string());
  }
  f.width_ = int(width);
  f.height_ = int(height);
  f.domainLog2_ = int(domainLog2);
  f.leafLevel_ = int(leafLevel);
  if (count == 0) return makeError("BDAM patch file {} holds no patch (corrupt file)", path.string());
  std::vector<std::byte> table(std::size_t(count) * kEntryBytes);
  if (!table.empty() && ::pread(f.fd_, table.data(), table.size(), off_t(kHeaderBytes)) != ssize_t(table.size())) {
    return makeError("BDAM patch file {}: cannot read its table", path.string());
  }
  if (!store_format::checksumMatches(XXH64(table.data(), table.size(), 0), getField<std::uint64_t>(header, 44))) {
    return makeError("BDAM patch file {}: its table fails its checksum (corrupt file)", path.string());
  }
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t at = i * kEntryBytes;
    PatchEntry e;
    e.node = getField<std::uint64_t>(table, at);
    e.offset = getField<std::uint64_t>(table, at + 8);
    e.bytes = getField<std::uint32_t>(table, at + 16);
    e.vertices = getField<std::uint32_t>(table, at + 20);
    e.indices = getField<std::uint32_t>(table, at + 24);
    e.errorM = getField<float>(table, at + 28);
    e.minZ = getField<float>(table, at + 32);
    e.maxZ = getField<float>(table, at + 36);
    e.origin = {getField<std::uint32_t>(table, at + 40), getField<std::uint32_t>(table, at + 44)};
    e.checksum = getField<std::uint64_t>(table, at + 48);
    const int level = nodeLevel(e.node);
    if (e.node < 2 || level > f.leafLevel_ || e.offset < kHeaderBytes + table.size() ||
        e.offset > f.fileBytes_ || e.bytes > f.fileBytes_ - e.offset ||
        std::uint64_t(e.vertices) * sizeof(PackedVertex) + std::uint64_t(e.indices) * 2 != e.bytes ||
        e.indices % 3 != 0 || e.vertices < 3 || e.vertices > 0xffff || (i > 0 && e.node <= f.entries_.back().node)) {
      return makeError("BDAM patch file {}: table entry {} is corrupt", path.string(), i);
    }
    if (!finite(e.errorM) || e.errorM < 0.0f || !finite(e.minZ) || !finite(e.maxZ) || e.minZ > e.maxZ ||
        e.origin.x >= std::uint32_t(f.width_) || e.origin.y >= std::uint32_t(f.height_)) {
      return makeError("BDAM patch file {}: patch {} has impossible values (error {} m, heights "
                       "{}..{} m, origin {}, {}): corrupt file",
                       path.string(), e.node, e.errorM, e.minZ, e.maxZ, e.origin.x, e.origin.y);
    }
    f.entries_.push_back(e);
  }
  return f;
}

PatchFile::PatchFile(PatchFile&& other) noexcept { *this = std::move(other); }
PatchFile& PatchFile::operator=(PatchFile&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    path_ = std::move(other.path_);
    fd_ = std::exchange(other.fd_, -1);
    width_ = other.width_;
    height_ = other.height_;
    domainLog2_ = other.domainLog2_;
    leafLevel_ = other.leafLevel_;
    spacingX_ = other.spacingX_;
    spacingY_ = other.spacingY_;
    fileBytes_ = other.fileBytes_;
    entries_ = std::move(other.entries_);
  }
  return *this;
}
PatchFile::~PatchFile() {
  if (fd_ >= 0) ::close(fd_);
}

Status PatchFile::read(std::size_t index, std::vector<PackedVertex>& vertices, std::vector<std::uint16_t>& indices) const {
  const PatchEntry& e = entries_[index];
  std::vector<std::byte> bytes(e.bytes);
  if (::pread(fd_, bytes.data(), bytes.size(), off_t(e.offset)) != ssize_t(bytes.size())) {
    return makeError("BDAM patch file {}: cannot read patch {}", path_.string(), e.node);
  }
  if (!store_format::checksumMatches(XXH64(bytes.data(), bytes.size(), 0), e.checksum)) {
    return makeError("BDAM patch file {}: patch {} fails its checksum (corrupt file)", path_.string(), e.node);
  }
  vertices.resize(e.vertices);
  indices.resize(e.indices);
  std::memcpy(vertices.data(), bytes.data(), e.vertices * sizeof(PackedVertex));
  std::memcpy(indices.data(), bytes.data() + e.vertices * sizeof(PackedVertex), e.indices * sizeof(std::uint16_t));
  // What the checksum cannot vouch for (it was made by whoever wrote the file): every index
  // names a vertex, every vertex lies on the grid with a finite height within the table's range.
  for (std::size_t k = 0; k < indices.size(); ++k) {
    if (indices[k] >= e.vertices) {
      return makeError("BDAM patch file {}: patch {} index {} is {}, beyond its {} vertices (corrupt file)",
                       path_.string(), e.node, k, indices[k], e.vertices);
    }
  }
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    const PackedVertex& v = vertices[k];
    if (!finite(v.heightM) || v.heightM < e.minZ || v.heightM > e.maxZ ||
        std::uint64_t(e.origin.x) + v.x >= std::uint64_t(width_) ||
        std::uint64_t(e.origin.y) + v.y >= std::uint64_t(height_)) {
      return makeError("BDAM patch file {}: patch {} vertex {} is at ({}, {}) with height {} m, off "
                       "the {} x {} grid or outside the patch's {}..{} m (corrupt file)",
                       path_.string(), e.node, k, std::uint64_t(e.origin.x) + v.x,
                       std::uint64_t(e.origin.y) + v.y, v.heightM, width_, height_, e.minZ, e.maxZ);
    }
  }
  return {};
}

}  // namespace tellus::bdam
