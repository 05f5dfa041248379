#include "tellus/tiles/store_metadata.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

namespace tellus {
using nlohmann::json;

std::string metadataToJson(const StoreMetadata& m) {
  json levels = json::array();
  for (int level = 0; level < m.layout.levelCount(); ++level) {
    levels.push_back({{"level", level},
                      {"tiles_x", m.layout.tilesX(level)},
                      {"tiles_y", m.layout.tilesY(level)},
                      {"spacing_x_m", m.spacingXM * PyramidLayout::stride(level)},
                      {"spacing_y_m", m.spacingYM * PyramidLayout::stride(level)}});
  }
  const json j = {
      {"format", "tellus-tile-store"},
      {"tile_size", m.layout.tileSize()},
      {"data_width", m.layout.dataWidth()},
      {"data_height", m.layout.dataHeight()},
      {"levels", levels},
      {"codec", m.codec},
      {"quantum_m", m.quantumM},
      {"max_error_m", m.maxErrorM},
      {"max_error_steps", m.maxErrorSteps},
      {"max_error_measured", m.maxErrorMeasured},
      {"zstd_level", m.zstdLevel},
      {"vertical_unit", "metre"},
      {"spacing_x_m", m.spacingXM},
      {"spacing_y_m", m.spacingYM},
      {"min_height_m", m.minHeightM},
      {"max_height_m", m.maxHeightM},
      {"filled_voids", m.filledVoidCount},
      {"georef",
       {{"crs_wkt", m.georef.crsWkt},
        {"crs_name", m.georef.crsName},
        {"has_geotransform", m.georef.hasGeoTransform},
        {"geotransform", m.georef.geoTransform},
        {"is_geographic", m.georef.isGeographic}}},
      {"sources", m.sources},
      {"producer", m.producer},
  };
  return j.dump(1);
}

Result<StoreMetadata> metadataFromJson(std::string_view text) {
  const json j = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) return makeError("metadata is not a JSON object");
  StoreMetadata m;
  try {
    if (j.at("format").get<std::string>() != "tellus-tile-store") {
      return makeError("metadata is not of a Tellus tile store");
    }
    Result<PyramidLayout> layout =
        PyramidLayout::create(j.at("data_width").get<int>(), j.at("data_height").get<int>(),
                              j.at("tile_size").get<int>());
    if (!layout)
      return makeError("metadata describes an invalid pyramid: {}", layout.error().message);
    m.layout = layout.value();
    if (j.at("levels").size() != std::size_t(m.layout.levelCount())) {
      return makeError("metadata lists {} levels, its pyramid has {}", j.at("levels").size(),
                       m.layout.levelCount());
    }
    m.codec = j.at("codec").get<std::string>();
    m.quantumM = j.at("quantum_m").get<double>();
    m.maxErrorM = j.at("max_error_m").get<double>();
    m.maxErrorSteps = j.at("max_error_steps").get<std::uint32_t>();
    m.maxErrorMeasured = j.value("max_error_measured", false);
    m.zstdLevel = j.at("zstd_level").get<int>();
    m.spacingXM = j.at("spacing_x_m").get<double>();
    m.spacingYM = j.at("spacing_y_m").get<double>();
    m.minHeightM = j.at("min_height_m").get<float>();
    m.maxHeightM = j.at("max_height_m").get<float>();
    m.filledVoidCount = j.at("filled_voids").get<std::size_t>();
    const json& g = j.at("georef");
    m.georef.crsWkt = g.at("crs_wkt").get<std::string>();
    m.georef.crsName = g.at("crs_name").get<std::string>();
    m.georef.hasGeoTransform = g.at("has_geotransform").get<bool>();
    m.georef.geoTransform = g.at("geotransform").get<std::array<double, 6>>();
    m.georef.isGeographic = g.at("is_geographic").get<bool>();
    m.sources = j.at("sources").get<std::vector<std::string>>();
    m.producer = j.at("producer").get<std::string>();
  } catch (const json::exception& e) {
    return makeError("metadata field missing or of the wrong type ({})", e.what());
  }
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(m.quantumM) || !positive(m.spacingXM) || !positive(m.spacingYM) ||
      !std::isfinite(m.maxErrorM) || m.maxErrorM < 0.0) {
    return makeError("metadata has a non-positive quantum, spacing or error bound");
  }
  return m;
}

}  // namespace tellus
