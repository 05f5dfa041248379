#include "tellus/lod/globe/globe_mesh.hpp"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "tellus/core/enu_frame.hpp"
#include "tellus/core/geodesy.hpp"

namespace tellus::globe {
namespace {

std::uint32_t packNormal(const glm::dvec3& n) {
  const auto component = [](double v) {
    const int i = int(std::lround(std::clamp(v, -1.0, 1.0) * 511.0));
    return std::uint32_t(i) & 0x3FFu;
  };
  return component(n.x) | (component(n.y) << 10) | (component(n.z) << 20);
}

}  // namespace

glm::vec3 unpackNormal(std::uint32_t packed) {
  const auto component = [](std::uint32_t bits) {
    int v = int(bits & 0x3FFu);
    if (v >= 512) v -= 1024;
    return std::max(float(v) / 511.0f, -1.0f);
  };
  return {component(packed), component(packed >> 10), component(packed >> 20)};
}

double sampleLatitudeDeg(const HeightGrid& grid, double row) {
  const auto& gt = grid.georef.geoTransform;
  return gt[3] + (row + 0.5) * gt[5];
}

double sampleLongitudeDeg(const HeightGrid& grid, double col) {
  const auto& gt = grid.georef.geoTransform;
  return gt[0] + (col + 0.5) * gt[1];
}

Result<GlobeMesh> buildGlobeMesh(const HeightGrid& grid, const Geoid* geoid, int chunkQuads,
                                 double skirtM) {
  const GeoReference& g = grid.georef;
  if (!g.isGeographic || !g.hasGeoTransform || g.geoTransform[2] != 0.0 ||
      g.geoTransform[4] != 0.0) {
    return makeError(
        "the globe needs a DEM in latitude/longitude (a geographic CRS, north up); this one is "
        "'{}'",
        g.crsName.empty() ? std::string("without a CRS") : g.crsName);
  }
  if (grid.width < 2 || grid.height < 2) return makeError("the globe needs at least 2 x 2 samples");
  const double north = sampleLatitudeDeg(grid, 0.0);
  const double south = sampleLatitudeDeg(grid, grid.height - 1);
  if (north > 90.0 + 1e-9 || south < -90.0 - 1e-9) {
    return makeError("the DEM's samples reach latitudes {} to {}, beyond the poles", south, north);
  }
  if (chunkQuads < 1) return makeError("chunks need at least one cell");
  if (!(skirtM >= 0.0)) return makeError("a skirt of {} m: it must be 0 or more", skirtM);

  GlobeMesh mesh;
  const double stepLon = g.geoTransform[1];
  mesh.wrapsLongitude = std::abs(grid.width * stepLon - 360.0) < 1e-6 * 360.0;
  if (mesh.wrapsLongitude && skirtM > 0.0) {
    return makeError("a grid around all longitudes has no edge to hang a skirt from");
  }
  const int pad = skirtM > 0.0 ? 1 : 0;  // the skirt's ring of vertices around the grid
  const int columns = grid.width + (mesh.wrapsLongitude ? 1 : 0);
  const auto heightAt = [&](int col, int row) { return grid.at(col % grid.width, row); };

  // Every sample's ECEF position once (double), then chunks copy theirs.
  const std::size_t count = std::size_t(columns) * std::size_t(grid.height);
  std::vector<glm::dvec3> ecef(count);
  std::vector<double> latRad(static_cast<std::size_t>(grid.height));
  std::vector<double> lonRad(static_cast<std::size_t>(columns));
  for (int row = 0; row < grid.height; ++row) {
    latRad[std::size_t(row)] =
        std::clamp(sampleLatitudeDeg(grid, row), -90.0, 90.0) * wgs84::kDegree;
  }
  for (int col = 0; col < columns; ++col) {
    lonRad[std::size_t(col)] = sampleLongitudeDeg(grid, col) * wgs84::kDegree;
  }
  for (int row = 0; row < grid.height; ++row) {
    const double lat = latRad[std::size_t(row)];
    for (int col = 0; col < columns; ++col) {
      const double lon = lonRad[std::size_t(col)];
      const double n = geoid ? geoid->undulationM(lat / wgs84::kDegree, lon / wgs84::kDegree) : 0.0;
      ecef[std::size_t(row) * std::size_t(columns) + std::size_t(col)] =
          wgs84::geodeticToEcef({lat, lon, heightAt(col, row) + n});
    }
  }
  const auto at = [&](int col, int row) {
    col = std::clamp(col, 0, columns - 1);
    row = std::clamp(row, 0, grid.height - 1);
    return ecef[std::size_t(row) * std::size_t(columns) + std::size_t(col)];
  };
  const auto neighbourColumn = [&](int col) {
    // Across the seam of a wrapped grid the neighbour is on the other side.
    if (!mesh.wrapsLongitude) return col;
    if (col < 0) return col + grid.width;
    if (col > columns - 1) return col - grid.width;
    return col;
  };

  // Chunks cover the grid with its skirt ring: padded (col, row) = grid (col - pad, row - pad),
  // the ring clamped onto the edge samples and lowered by skirtM.
  const int paddedColumns = columns + 2 * pad, paddedRows = grid.height + 2 * pad;
  for (int row0 = 0; row0 < paddedRows - 1; row0 += chunkQuads) {
    for (int col0 = 0; col0 < paddedColumns - 1; col0 += chunkQuads) {
      GlobeChunk chunk;
      chunk.vertsX = std::min(chunkQuads, paddedColumns - 1 - col0) + 1;
      chunk.vertsY = std::min(chunkQuads, paddedRows - 1 - row0) + 1;
      chunk.vertices.reserve(std::size_t(chunk.vertsX) * std::size_t(chunk.vertsY));
      glm::dvec3 low(1e300), high(-1e300);
      for (int j = 0; j < chunk.vertsY; ++j) {
        for (int i = 0; i < chunk.vertsX; ++i) {
          const int paddedCol = col0 + i, paddedRow = row0 + j;
          const int col = std::clamp(paddedCol - pad, 0, columns - 1);
          const int row = std::clamp(paddedRow - pad, 0, grid.height - 1);
          const bool skirt = pad > 0 && (paddedCol == 0 || paddedRow == 0 ||
                                         paddedCol == paddedColumns - 1 ||
                                         paddedRow == paddedRows - 1);
          const std::size_t index = std::size_t(row) * std::size_t(columns) + std::size_t(col);
          glm::dvec3 p = ecef[index];
          if (skirt) {
            const double lat = latRad[std::size_t(row)], lon = lonRad[std::size_t(col)];
            const double n =
                geoid ? geoid->undulationM(lat / wgs84::kDegree, lon / wgs84::kDegree) : 0.0;
            p = wgs84::geodeticToEcef({lat, lon, heightAt(col, row) + n - skirtM});
          }
          GlobeVertex v;
          splitEcef(p, v.whole, v.fraction);
          v.heightM = heightAt(col, row);
          // Normal from central differences, in the vertex's own ENU frame. At a pole row the
          // east-west difference vanishes: the ellipsoid normal (up) is used there. A skirt
          // vertex takes its edge sample's normal (lit like the ground above it).
          const glm::dvec3 dx = at(neighbourColumn(col + 1), row) - at(neighbourColumn(col - 1), row);
          const glm::dvec3 dy = at(col, row - 1) - at(col, row + 1);  // towards the north
          glm::dvec3 normal = glm::cross(dx, dy);
          const EnuAxes frame = EnuAxes::at(latRad[std::size_t(row)], lonRad[std::size_t(col)]);
          glm::dvec3 local = glm::length(normal) > 1e-9
                                 ? glm::dvec3(glm::dot(normal, frame.east),
                                              glm::dot(normal, frame.north),
                                              glm::dot(normal, frame.up))
                                 : glm::dvec3(0.0, 0.0, 1.0);
          local = glm::normalize(local);
          if (local.z < 0.0) local = -local;  // grids stored south-up or east-left
          v.normal = packNormal(local);
          chunk.vertices.push_back(v);
          low = glm::min(low, p);
          high = glm::max(high, p);
        }
      }
      chunk.ecefBounds = {low, high};
      mesh.vertexCount += chunk.vertices.size();
      mesh.triangleCount += std::uint64_t(chunk.vertsX - 1) * std::uint64_t(chunk.vertsY - 1) * 2;
      mesh.chunks.push_back(std::move(chunk));
    }
  }
  return mesh;
}

}  // namespace tellus::globe
