// tellus::exportGlb (include/tellus/terrain_export.hpp): the glTF export of a Terrain's store.
#include "tellus/terrain_export.hpp"

#include "terrain_state.hpp"
#include "tellus/export/gltf_export.hpp"

namespace tellus {

Result<MeshExportSummary> exportGlb(const Terrain& terrain, const std::string& path,
                                    const MeshExportSettings& settings) {
  GltfExportOptions options;
  if (settings.region) {
    const GeographicBox& box = *settings.region;
    options.region = LonLatBox{box.westDeg, box.southDeg, box.eastDeg, box.northDeg};
  }
  options.maxErrorM = settings.maxErrorM;
  options.hypsometricColours = settings.hypsometricColours;
  options.quantize = settings.quantize;
  options.texture = settings.texture;
  auto report = exportGltf(*terrain.state().store, path, options);
  if (!report) return report.error();
  return MeshExportSummary{report.value().vertices, report.value().triangles, report.value().bytes,
                           report.value().maxErrorM, report.value().storeLevel};
}

}  // namespace tellus
