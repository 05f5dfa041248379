#pragma once
// Tellus's public API: a terrain, or a region of it, as one binary glTF 2.0 mesh (.glb) within
// a given error: the same as `tellus export STORE --gltf out.glb`.
#include <cstdint>
#include <optional>
#include <string>

#include "tellus/result.hpp"
#include "tellus/terrain.hpp"

namespace tellus {

// A longitude/latitude box, WGS84 degrees.
struct GeographicBox {
  double westDeg = 0.0, southDeg = 0.0, eastDeg = 0.0, northDeg = 0.0;
};

struct MeshExportSettings {
  std::optional<GeographicBox> region;  // the whole terrain when unset
  double maxErrorM = 1.0;               // every sample within this of the mesh (3-D), metres
  bool hypsometricColours = false;      // vertex colours by height
  bool quantize = false;                // KHR_mesh_quantization: smaller files
  std::string texture;                  // a georeferenced RGB image draped on it; empty: none
};

struct MeshExportSummary {
  std::uint64_t vertices = 0, triangles = 0;
  std::uint64_t bytes = 0;   // of the .glb
  double maxErrorM = 0.0;    // measured against the samples of the level used
  int storeLevel = 0;        // the pyramid level the mesh was built from (0: finest)
};

// Writes `path` through a temporary file (never a half-written .glb; an existing file is only
// replaced once the new one is complete). Errors: a region outside the terrain, a terrain
// without georeferencing, a bound that is not a positive finite number, write failures.
Result<MeshExportSummary> exportGlb(const Terrain& terrain, const std::string& path,
                                    const MeshExportSettings& settings = {});

}  // namespace tellus
