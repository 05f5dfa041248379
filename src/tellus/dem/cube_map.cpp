#include "tellus/dem/cube_map.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

namespace tellus {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Catmull-Rom weights (Keys, a = -0.5) for the four taps round a fraction t in [0, 1).
std::array<double, 4> cubicWeights(double t) {
  const double t2 = t * t, t3 = t2 * t;
  return {-0.5 * t3 + t2 - 0.5 * t, 1.5 * t3 - 2.5 * t2 + 1.0, -1.5 * t3 + 2.0 * t2 + 0.5 * t,
          0.5 * t3 - 0.5 * t2};
}

// The face and its (column, row) in texels for a direction (OpenGL's major-axis rule).
void faceOf(const glm::dvec3& r, int size, int& face, double& column, double& row) {
  const double ax = std::abs(r.x), ay = std::abs(r.y), az = std::abs(r.z);
  double sc = 0.0, tc = 0.0, ma = 1.0;
  if (ax >= ay && ax >= az) {
    face = r.x > 0.0 ? 0 : 1;
    sc = r.x > 0.0 ? -r.z : r.z;
    tc = -r.y;
    ma = ax;
  } else if (ay >= az) {
    face = r.y > 0.0 ? 2 : 3;
    sc = r.x;
    tc = r.y > 0.0 ? r.z : -r.z;
    ma = ay;
  } else {
    face = r.z > 0.0 ? 4 : 5;
    sc = r.z > 0.0 ? r.x : -r.x;
    tc = -r.y;
    ma = az;
  }
  column = 0.5 * (sc / ma + 1.0) * size - 0.5;
  row = 0.5 * (tc / ma + 1.0) * size - 0.5;
}

}  // namespace

glm::dvec3 cubeTexelDirection(int face, int size, double column, double row) {
  const double a = 2.0 * (column + 0.5) / size - 1.0;
  const double b = 2.0 * (row + 0.5) / size - 1.0;
  glm::dvec3 r(0.0);
  switch (face) {
    case 0: r = {1.0, -b, -a}; break;
    case 1: r = {-1.0, -b, a}; break;
    case 2: r = {a, 1.0, b}; break;
    case 3: r = {a, -1.0, -b}; break;
    case 4: r = {a, -b, 1.0}; break;
    default: r = {-a, -b, -1.0}; break;
  }
  return glm::normalize(r);
}

double sampleLatLonBicubic(const LatLonImage& image, double latDeg, double lonDeg, int channel) {
  // Pixel centres: column i at lon -180 + (i + 0.5) * 360 / width.
  const double x = (lonDeg + 180.0) / 360.0 * image.width - 0.5;
  const double y = (90.0 - latDeg) / 180.0 * image.height - 0.5;
  const double x0 = std::floor(x), y0 = std::floor(y);
  const std::array<double, 4> wx = cubicWeights(x - x0), wy = cubicWeights(y - y0);
  double sum = 0.0;
  for (int j = 0; j < 4; ++j) {
    const int row = std::clamp(int(y0) - 1 + j, 0, image.height - 1);
    double rowSum = 0.0;
    for (int i = 0; i < 4; ++i) {
      int column = (int(x0) - 1 + i) % image.width;
      if (column < 0) column += image.width;  // longitudes wrap
      rowSum += wx[std::size_t(i)] *
                image.pixels[(std::size_t(row) * std::size_t(image.width) + std::size_t(column)) *
                                 std::size_t(image.channels) + std::size_t(channel)];
    }
    sum += wy[std::size_t(j)] * rowSum;
  }
  return sum;
}

CubeMap latLonToCubeMap(const LatLonImage& source, int size) {
  CubeMap cube;
  cube.size = size;
  cube.channels = source.channels;
  for (auto& face : cube.faces) {
    face.assign(std::size_t(size) * std::size_t(size) * std::size_t(source.channels), 0);
  }
  if (source.pixels.empty()) return cube;
  tbb::parallel_for(0, 6 * size, [&](int faceRow) {
    const int face = faceRow / size, row = faceRow % size;
    std::uint8_t* out = cube.faces[std::size_t(face)].data() +
                        std::size_t(row) * std::size_t(size) * std::size_t(source.channels);
    for (int column = 0; column < size; ++column) {
      const glm::dvec3 d = cubeTexelDirection(face, size, column, row);
      const double lat = std::atan2(d.z, std::hypot(d.x, d.y)) * 180.0 / kPi;
      const double lon = std::atan2(d.y, d.x) * 180.0 / kPi;
      for (int c = 0; c < source.channels; ++c) {
        const double v = sampleLatLonBicubic(source, lat, lon, c);
        out[std::size_t(column) * std::size_t(source.channels) + std::size_t(c)] =
            std::uint8_t(std::clamp(std::lround(v), 0L, 255L));
      }
    }
  });
  return cube;
}

double sampleCubeMap(const CubeMap& cube, const glm::dvec3& direction, int channel) {
  int face = 0;
  double column = 0.0, row = 0.0;
  faceOf(direction, cube.size, face, column, row);
  column = std::clamp(column, 0.0, cube.size - 1.0);
  row = std::clamp(row, 0.0, cube.size - 1.0);
  const int c0 = std::min(int(column), cube.size - 2), r0 = std::min(int(row), cube.size - 2);
  const double fc = column - c0, fr = row - r0;
  const auto at = [&](int c, int r) {
    return double(cube.faces[std::size_t(face)][(std::size_t(r) * std::size_t(cube.size) +
                                                 std::size_t(c)) * std::size_t(cube.channels) +
                                                std::size_t(channel)]);
  };
  const double top = at(c0, r0) + (at(c0 + 1, r0) - at(c0, r0)) * fc;
  const double bottom = at(c0, r0 + 1) + (at(c0 + 1, r0 + 1) - at(c0, r0 + 1)) * fc;
  return top + (bottom - top) * fr;
}

}  // namespace tellus
