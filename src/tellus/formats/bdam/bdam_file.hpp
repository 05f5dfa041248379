#pragma once
// The BDAM patch file (`tellus build --bdam` writes NAME.bdam beside NAME.tstore): a header, a
// table of every patch (node, error, height range, where its data lies, checksum) read whole at
// open, and each patch's data read on demand (pread), checked against its xxHash64.
//
// Layout (little-endian), format 2:
//   header, 64 bytes: "TBDAMv2\0", grid width u32, height u32, domainLog2 u32, leafLevel u32,
//     patch count u32, spacing x f64, spacing y f64, table checksum u64, header checksum u64
//     (xxh64 of the 52 bytes before it), zero padding
//   table: per patch 56 bytes: node u64, data offset u64, data bytes u32, vertices u32,
//     indices u32, error f32, min z f32, max z f32, origin x u32, origin y u32, checksum u64
//   data: per patch, its vertices (x - origin x u16, y - origin y u16, height f32) then its
//     indices (u16, three per counter-clockwise triangle)
#include <cstdint>
#include <filesystem>
#include <vector>

#include <glm/vec2.hpp>

#include "tellus/formats/bdam/bdam_patches.hpp"
#include "tellus/core/result.hpp"

namespace tellus::bdam {

// One patch as the GPU takes it: positions relative to the origin, 8 bytes a vertex.
struct PackedVertex {
  std::uint16_t x = 0, y = 0;  // samples east / north of the patch's origin
  float heightM = 0.0f;
};

struct PatchEntry {
  NodeId node = 0;
  std::uint64_t offset = 0;
  std::uint32_t bytes = 0;
  std::uint32_t vertices = 0;
  std::uint32_t indices = 0;
  float errorM = 0.0f;
  float minZ = 0.0f, maxZ = 0.0f;
  glm::uvec2 origin{0};
  std::uint64_t checksum = 0;
};

// Writes the hierarchy to `path` (through a temporary file renamed at the end: never a
// half-written file). Returns the bytes written.
Result<std::uint64_t> writePatchFile(const Hierarchy& hierarchy, const std::filesystem::path& path);

class PatchFile {
 public:
  // Errors name the file and what is wrong: not a patch file, format 1 (rebuild it), header or
  // table checksum, no patch, impossible values in the table (a negative or NaN error, min above
  // max, an origin off the grid, data outside the file).
  static Result<PatchFile> open(const std::filesystem::path& path);
  PatchFile() = default;  // no file: no entries
  PatchFile(PatchFile&&) noexcept;
  PatchFile& operator=(PatchFile&&) noexcept;
  ~PatchFile();

  int gridWidth() const { return width_; }
  int gridHeight() const { return height_; }
  double spacingXM() const { return spacingX_; }
  double spacingYM() const { return spacingY_; }
  int domainLog2() const { return domainLog2_; }
  int leafLevel() const { return leafLevel_; }
  const std::vector<PatchEntry>& entries() const { return entries_; }
  std::uint64_t fileBytes() const { return fileBytes_; }

  // Reads patch `index`'s data. Thread-safe. Errors: a read failure, a checksum mismatch, an
  // index beyond the patch's vertices, a vertex off the grid or with a height that is not
  // finite or outside the table's min..max (a checksum recomputed over forged data).
  Status read(std::size_t index, std::vector<PackedVertex>& vertices, std::vector<std::uint16_t>& indices) const;

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  int width_ = 0, height_ = 0, domainLog2_ = 0, leafLevel_ = 0;
  double spacingX_ = 1.0, spacingY_ = 1.0;
  std::uint64_t fileBytes_ = 0;
  std::vector<PatchEntry> entries_;
};

// NAME.bdam for NAME.tstore (or any input path): where bench, render and view look for BDAM's
// patches by default.
std::filesystem::path defaultPatchFilePath(const std::filesystem::path& input);

}  // namespace tellus::bdam
