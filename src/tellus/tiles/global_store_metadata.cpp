#include "tellus/tiles/global_store_metadata.hpp"

#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "tellus/tiles/metadata_json.hpp"
#include "tellus/tiles/pyramid_layout.hpp"
#include "tellus/tiles/store_metadata.hpp"

namespace tellus {
using nlohmann::json;

std::string globalMetadataToJson(const GlobalStoreMetadata& m) {
  json sources = json::array();
  for (const GlobalStoreSource& s : m.sources) {
    sources.push_back({{"path", s.path},
                       {"west_deg", s.bounds.westDeg},
                       {"south_deg", s.bounds.southDeg},
                       {"east_deg", s.bounds.eastDeg},
                       {"north_deg", s.bounds.northDeg},
                       {"spacing_deg", s.spacingDeg},
                       {"depth", s.depth}});
  }
  const json j = {
      {"format", "tellus-global-store"},
      {"tiling", "geographic: two 180-degree root tiles, a latitude/longitude quadtree"},
      {"tile_cells", m.tileCells},
      {"deepest_depth", m.deepestDepth},
      {"tiles_per_depth", m.tilesPerDepth},
      {"codec", m.codec},
      {"quantum_m", m.quantumM},
      {"max_error_m", m.maxErrorM},
      {"max_error_steps", m.maxErrorSteps},
      {"zstd_level", m.zstdLevel},
      {"vertical_unit", "metre"},
      {"height_reference", "as the sources give it (above the geoid for SRTM, BIL, ETOPO)"},
      {"min_height_m", m.minHeightM},
      {"max_height_m", m.maxHeightM},
      {"north_pole_m", m.northPoleM},
      {"south_pole_m", m.southPoleM},
      {"uncovered_samples", m.uncoveredSamples},
      {"zero_yields_to_sea_floor", m.zeroYieldsToSeaFloor},
      {"edge_blend_m", m.edgeBlendM},
      {"sources", sources},
      {"producer", m.producer},
  };
  return j.dump(1);
}

namespace {

using metadata_json::kMaxAbsHeightM;
using metadata_json::numberField;

double number(const json& j, const char* key, double lo, double hi) {
  return numberField<double>(j, key, lo, hi);
}

std::int64_t integer(const json& j, const char* key, double lo, double hi) {
  return numberField<std::int64_t>(j, key, lo, hi);
}

GlobalStoreMetadata parse(const json& j) {
  if (j.at("format").get<std::string>() != "tellus-global-store") {
    throw std::invalid_argument("it is not the metadata of a Tellus global store");
  }
  GlobalStoreMetadata m;
  m.tileCells = int(integer(j, "tile_cells", 16, PyramidLayout::kMaxTileSize));
  if ((m.tileCells & (m.tileCells - 1)) != 0) {
    throw std::invalid_argument(fmt::format("'tile_cells' {} is not a power of two", m.tileCells));
  }
  m.deepestDepth = int(integer(j, "deepest_depth", 0, GlobalTiling::kMaxDepth));
  const json& perDepth = j.at("tiles_per_depth");
  if (!perDepth.is_array() || perDepth.size() != std::size_t(m.deepestDepth + 1)) {
    throw std::invalid_argument("'tiles_per_depth' does not list every depth");
  }
  for (std::size_t d = 0; d < perDepth.size(); ++d) {
    const double most = double(GlobalTiling::tilesX(int(d))) * double(GlobalTiling::tilesY(int(d)));
    const json& v = perDepth[d];
    if (!v.is_number_unsigned() || double(v.get<std::uint64_t>()) > most ||
        (d == 0 && v.get<std::uint64_t>() != 2) || v.get<std::uint64_t>() == 0) {
      throw std::invalid_argument(fmt::format("'tiles_per_depth' entry {} is impossible", d));
    }
    m.tilesPerDepth.push_back(v.get<std::uint64_t>());
  }
  m.codec = j.at("codec").get<std::string>();
  m.quantumM = number(j, "quantum_m", kMinQuantumM, kMaxQuantumM);
  m.maxErrorM = number(j, "max_error_m", 0.0, kMaxAbsHeightM);
  m.maxErrorSteps = std::uint32_t(integer(j, "max_error_steps", 0, 1e9));
  m.zstdLevel = int(integer(j, "zstd_level", 0, 22));
  m.minHeightM = float(number(j, "min_height_m", -kMaxAbsHeightM, kMaxAbsHeightM));
  m.maxHeightM = float(number(j, "max_height_m", -kMaxAbsHeightM, kMaxAbsHeightM));
  if (!(m.minHeightM <= m.maxHeightM)) {
    throw std::invalid_argument(fmt::format("its lowest height {} m is above its highest {} m",
                                            m.minHeightM, m.maxHeightM));
  }
  m.northPoleM = float(number(j, "north_pole_m", m.minHeightM, m.maxHeightM));
  m.southPoleM = float(number(j, "south_pole_m", m.minHeightM, m.maxHeightM));
  m.uncoveredSamples = std::uint64_t(integer(j, "uncovered_samples", 0, 1e18));
  if (j.contains("zero_yields_to_sea_floor")) {
    if (!j.at("zero_yields_to_sea_floor").is_boolean()) {
      throw std::invalid_argument("'zero_yields_to_sea_floor' is not true or false");
    }
    m.zeroYieldsToSeaFloor = j.at("zero_yields_to_sea_floor").get<bool>();
  }
  if (j.contains("edge_blend_m")) m.edgeBlendM = number(j, "edge_blend_m", 0.0, kMaxEdgeBlendM);
  // Every stored depth is fed by a source: at least one, and the deepest feeds deepest_depth.
  const json& sources = j.at("sources");
  if (!sources.is_array() || sources.empty()) {
    throw std::invalid_argument("'sources' lists no source (a global store is built from one or more)");
  }
  if (sources.size() > 100000) throw std::invalid_argument("'sources' lists more than 100000 sources");
  int deepestSource = -1;
  for (const json& s : sources) {
    GlobalStoreSource source;
    source.path = s.at("path").get<std::string>();
    source.bounds = {number(s, "west_deg", -181, 181), number(s, "south_deg", -91, 91),
                     number(s, "east_deg", -181, 181), number(s, "north_deg", -91, 91)};
    if (!(source.bounds.westDeg < source.bounds.eastDeg && source.bounds.southDeg < source.bounds.northDeg)) {
      throw std::invalid_argument(fmt::format("source '{}' has bounds that are not a box", source.path));
    }
    source.spacingDeg = number(s, "spacing_deg", 1e-9, 180);
    source.depth = int(integer(s, "depth", 0, m.deepestDepth));
    deepestSource = std::max(deepestSource, source.depth);
    m.sources.push_back(source);
  }
  if (deepestSource != m.deepestDepth) {
    throw std::invalid_argument(fmt::format("'deepest_depth' is {} but its sources feed depths "
                                            "0..{} only",
                                            m.deepestDepth, deepestSource));
  }
  m.producer = j.at("producer").get<std::string>();
  m.buildSeconds = j.value("build_seconds", 0.0);
  return m;
}

}  // namespace

Result<GlobalStoreMetadata> globalMetadataFromJson(std::string_view text) {
  return metadata_json::parseMetadataJson<GlobalStoreMetadata>(text, parse);
}

}  // namespace tellus
