#pragma once
// The .tstack file: a material-stack terrain and its level-of-detail pyramid (seed 003's
// "MipMap representation"), every level compressed and checksummed. Readers never trust it:
// every size, offset and column is checked before use, and errors say what and where.
//
// Layout (little endian):
//   header, 64 bytes: "TLSSTK01", u32 version (1, or 2 with a georeference), u32 levels, f64
//     level 0's spacing (metres), u64 georeference bytes (version 2; 0 in version 1), 16 bytes
//     reserved (0), u64 xxh64 of the header's first 56 bytes, the level table and the
//     georeference;
//   level table, 48 bytes a level: u32 width, u32 height, u64 layers, u64 block offset, u64
//     block bytes (compressed), u64 xxh64 of the block uncompressed, u64 reserved (0);
//   georeference (version 2 only): 6 f64 GDAL geotransform of level 0's stacks (pixel-is-area:
//     stack (x, y)'s centre at pixel (x + 1/2, y + 1/2)), u32 flags (bit 0: it has a
//     geotransform, bit 1: the CRS is geographic), u32 WKT bytes, u32 name bytes, the CRS's WKT
//     and short name (UTF-8, no terminator);
//   blocks: zstd frames, each a level's column offsets (u32, width x height + 1) then its layers
//     (f32 bottom, f32 top, u8 material: 9 bytes each).
// Level k + 1 is ceil(width / 2) x ceil(height / 2) of level k, at twice the spacing. Files
// without a georeference (generated terrains) are written as version 1, byte for byte as before.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/formats/stacks/material_stack.hpp"

namespace tellus {

// The tallest terrain a stack file may hold, in stack spacings: the density grids every stack
// renderer makes (cells of the stack spacing by default) count heights in 2^30 sub-cells.
inline constexpr double kMaxStackHeightInSpacings = double(1 << 22);

// A spacing within checkSampleSpacing()'s range and a top at most kMaxStackHeightInSpacings
// spacings high (the message does not name a file).
Status checkStackGeometry(double spacingM, float topM);

// Whether `georef` says anything (a CRS or a geotransform): only then is it written.
bool hasStackGeoReference(const GeoReference& georef);

// Writes `levels` (level 0 first, each half the one before) atomically, with `georef` (where
// level 0's stacks lie; none by default) when it says anything. Errors: levels that do not
// halve, a geometry checkStackGeometry() refuses, a georeference checkGeoReference() refuses,
// the disk.
Status writeStackFile(const std::filesystem::path& path, const std::vector<StackTerrain>& levels,
                      const GeoReference& georef = {});

struct StackFileSummary {
  int levels = 0;
  int width = 0, height = 0;  // level 0
  double spacingM = 0.0;
  std::uint64_t fileBytes = 0;
  std::uint64_t layers = 0;         // all levels
  std::uint64_t memoryBytes = 0;    // all levels, as StackTerrain holds them
  GeoReference georef;              // where level 0 lies (nothing for generated terrains)
};

// Reads and checks the whole file: every checksum and column, the blocks contiguous up to the
// file's end (nothing appended), a spacing and height checkStackGeometry() accepts, memory
// checked before every allocation (checkMemoryFor) and no block declaring more than zstd can
// expand it to. Does not check that each level is the aggregation of the one below
// (verifyStackPyramid does).
// With `georef`, the file's georeference is returned there too (one read of the header).
Result<std::vector<StackTerrain>> readStackFile(const std::filesystem::path& path,
                                                GeoReference* georef = nullptr);
// Only the georeference of a stack file (reads the header and checks its checksum; an empty
// GeoReference for a file without one). Errors as readStackFile's for the header.
Result<GeoReference> readStackGeoReference(const std::filesystem::path& path);
// That every level above the finest is exactly the aggregation of the one below it
// (aggregateStackTerrain), as writers make them: an edited or forged level is named.
Status verifyStackPyramid(const std::vector<StackTerrain>& levels);
// The same, summarised (tellus info / verify).
Result<StackFileSummary> summariseStackFile(const std::filesystem::path& path);

}  // namespace tellus
