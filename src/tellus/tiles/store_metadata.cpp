#include "tellus/tiles/store_metadata.hpp"

#include <cmath>
#include <stdexcept>
#include <type_traits>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "tellus/core/geotransform_check.hpp"
#include "tellus/tiles/metadata_json.hpp"

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

namespace {

using metadata_json::kMaxAbsHeightM;
using metadata_json::numberField;

// The "levels" array must describe the pyramid it belongs to.
void checkLevels(const json& levels, const StoreMetadata& m) {
  if (!levels.is_array() || levels.size() != std::size_t(m.layout.levelCount())) {
    throw std::invalid_argument(fmt::format("'levels' does not list the pyramid's {} levels",
                                            m.layout.levelCount()));
  }
  for (int level = 0; level < m.layout.levelCount(); ++level) {
    const json& l = levels.at(std::size_t(level));
    const double stride = PyramidLayout::stride(level);
    const bool same =
        numberField<std::int64_t>(l, "level", 0, 64) == level &&
        numberField<std::int64_t>(l, "tiles_x", 0, 1 << 30) == m.layout.tilesX(level) &&
        numberField<std::int64_t>(l, "tiles_y", 0, 1 << 30) == m.layout.tilesY(level) &&
        std::abs(l.at("spacing_x_m").get<double>() - m.spacingXM * stride) <=
            1e-9 * m.spacingXM * stride &&
        std::abs(l.at("spacing_y_m").get<double>() - m.spacingYM * stride) <=
            1e-9 * m.spacingYM * stride;
    if (!same) {
      throw std::invalid_argument(
          fmt::format("'levels' entry {} does not match the pyramid", level));
    }
  }
}

StoreMetadata parseMetadata(const json& j) {
  StoreMetadata m;
  if (j.at("format").get<std::string>() != "tellus-tile-store") {
    throw std::invalid_argument("it is not the metadata of a Tellus tile store");
  }
  Result<PyramidLayout> layout = PyramidLayout::create(
      numberField<int>(j, "data_width", 2, PyramidLayout::kMaxSide),
      numberField<int>(j, "data_height", 2, PyramidLayout::kMaxSide),
      numberField<int>(j, "tile_size", 16, PyramidLayout::kMaxTileSize));
  if (!layout) throw std::invalid_argument("it describes an invalid pyramid: " + layout.error().message);
  m.layout = layout.value();
  m.codec = j.at("codec").get<std::string>();
  m.quantumM = numberField<double>(j, "quantum_m", kMinQuantumM, kMaxQuantumM);
  m.maxErrorM = numberField<double>(j, "max_error_m", 0.0, kMaxAbsHeightM);
  m.maxErrorSteps = numberField<std::uint32_t>(j, "max_error_steps", 0, 1e9);
  m.maxErrorMeasured = j.value("max_error_measured", false);
  m.zstdLevel = numberField<int>(j, "zstd_level", 0, 22);
  m.spacingXM = numberField<double>(j, "spacing_x_m", kMinSampleSpacingM, kMaxSampleSpacingM);
  m.spacingYM = numberField<double>(j, "spacing_y_m", kMinSampleSpacingM, kMaxSampleSpacingM);
  m.minHeightM = numberField<float>(j, "min_height_m", -kMaxAbsHeightM, kMaxAbsHeightM);
  m.maxHeightM = numberField<float>(j, "max_height_m", -kMaxAbsHeightM, kMaxAbsHeightM);
  if (!(m.minHeightM <= m.maxHeightM)) {
    throw std::invalid_argument(fmt::format("its lowest height {} m is above its highest {} m",
                                            m.minHeightM, m.maxHeightM));
  }
  const double samples = double(m.layout.dataWidth()) * double(m.layout.dataHeight());
  m.filledVoidCount = numberField<std::size_t>(j, "filled_voids", 0, samples);
  checkLevels(j.at("levels"), m);
  const json& g = j.at("georef");
  m.georef.crsWkt = g.at("crs_wkt").get<std::string>();
  m.georef.crsName = g.at("crs_name").get<std::string>();
  m.georef.hasGeoTransform = g.at("has_geotransform").get<bool>();
  m.georef.geoTransform = g.at("geotransform").get<std::array<double, 6>>();
  m.georef.isGeographic = g.at("is_geographic").get<bool>();
  if (m.georef.hasGeoTransform) {
    if (Status gt = checkGeoTransform(m.georef.geoTransform, m.georef.isGeographic,
                                      m.layout.dataWidth(), m.layout.dataHeight());
        !gt) {
      throw std::invalid_argument(gt.error().message);
    }
  }
  m.sources = j.at("sources").get<std::vector<std::string>>();
  m.producer = j.at("producer").get<std::string>();
  return m;
}

}  // namespace

Result<StoreMetadata> metadataFromJson(std::string_view text) {
  return metadata_json::parseMetadataJson<StoreMetadata>(text, parseMetadata);
}

}  // namespace tellus
