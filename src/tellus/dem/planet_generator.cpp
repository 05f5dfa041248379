#include "tellus/dem/planet_generator.hpp"

#include "tellus/dem/gdal_support.hpp"

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>
#include <tbb/parallel_for.h>


#include "tellus/dem/gradient_noise.hpp"

namespace tellus {
namespace {

constexpr double kDegree = 3.14159265358979323846 / 180.0;

// Fractal noise on the unit sphere: `octaves` octaves of the triplanar blend, starting at
// `frequency` cycles per unit of the projected coordinates.
class SphereNoise {
 public:
  explicit SphereNoise(std::uint64_t seed) : planes_{GradientNoise(seed * 3 + 0),
                                                     GradientNoise(seed * 3 + 1),
                                                     GradientNoise(seed * 3 + 2)} {}

  double fbm(const glm::dvec3& q, double frequency, int octaves) const {
    glm::dvec3 w = q * q;
    w *= w;
    w /= (w.x + w.y + w.z);
    double sum = 0.0, amplitude = 0.5;
    for (int octave = 0; octave < octaves; ++octave) {
      const glm::dvec3 p = q * frequency + glm::dvec3(5.3, -2.9, 7.1) * double(octave);
      sum += amplitude * (w.x * planes_[0].sample({p.y, p.z}).x +
                          w.y * planes_[1].sample({p.z, p.x}).x +
                          w.z * planes_[2].sample({p.x, p.y}).x);
      frequency *= 2.0;
      amplitude *= 0.5;
    }
    return sum;
  }

 private:
  GradientNoise planes_[3];
};

glm::dvec3 unitVector(double latDeg, double lonDeg) {
  const double lat = latDeg * kDegree, lon = lonDeg * kDegree;
  return {std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat)};
}

// `height` at direction q, drawn to the plateau's height near its centre.
double blendPlateau(const PlanetPlateau& plateau, const glm::dvec3& q, double height) {
  const glm::dvec3 centre = unitVector(plateau.latDeg, plateau.lonDeg);
  const double angleDeg = std::acos(std::clamp(glm::dot(q, centre), -1.0, 1.0)) / kDegree;
  const double t = std::clamp((angleDeg - plateau.radiusDeg) / plateau.radiusDeg, 0.0, 1.0);
  const double weight = 1.0 - t * t * (3.0 - 2.0 * t);  // 1 inside, 0 beyond twice the radius
  return height + (plateau.heightM - height) * weight;
}

}  // namespace

HeightGrid generatePlanet(const PlanetParams& params) {
  int columns = std::clamp(params.columns, kMinPlanetColumns, kMaxPlanetColumns);
  columns += columns % 2;
  const int rows = columns / 2;
  const double step = 360.0 / columns;
  HeightGrid grid(columns, rows);
  const SphereNoise continents(params.seed * 2 + 0), mountains(params.seed * 2 + 1);
  const double scale = params.highestM;
  const bool plateau = params.plateau.has_value();
  tbb::parallel_for(0, rows, [&](int j) {
    const double lat = (90.0 - (j + 0.5) * step) * kDegree;
    for (int i = 0; i < columns; ++i) {
      const double lon = (-180.0 + (i + 0.5) * step) * kDegree;
      const glm::dvec3 q(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon),
                         std::sin(lat));  // (unitVector without the degree conversions)
      // Continents: large, smooth shapes; the coast where they cross 0.
      const double land = continents.fbm(q, 1.6, 7) - 0.01;
      // Mountain ranges: ridged noise, strongest inland.
      const double ridge = 1.0 - std::abs(mountains.fbm(q, 3.0, 6) * 2.0);
      const double inland = std::clamp(land / 0.15, 0.0, 1.0);
      const double height = land > 0.0
                                ? scale * (0.25 * land + 0.55 * inland * ridge * ridge * ridge)
                                : scale * 1.6 * std::max(land, -0.45) - 200.0;
      grid.at(i, j) = float(plateau ? blendPlateau(*params.plateau, q, height) : height);
    }
  });
  const double metresPerDegree = 6378137.0 * kDegree;
  grid.spacingXM = step * metresPerDegree;
  grid.spacingYM = step * metresPerDegree;
  grid.georef.crsWkt = gdal::wgs84Wkt();
  grid.georef.crsName = "WGS 84";
  grid.georef.isGeographic = true;
  grid.georef.hasGeoTransform = true;
  grid.georef.geoTransform = {-180.0, step, 0.0, 90.0, 0.0, -step};
  return grid;
}

}  // namespace tellus
