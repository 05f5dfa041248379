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

  // Octave k has frequency * 2^k and amplitude 0.5 * gain^k.
  double fbm(const glm::dvec3& q, double frequency, int octaves, double gain = 0.5) const {
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
      amplitude *= gain;
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

struct PlanetField::Noises {
  SphereNoise continents, mountains, detail;
};

PlanetField::PlanetField(const PlanetParams& params)
    : params_(params),
      noises_(std::make_unique<Noises>(Noises{SphereNoise(params.seed * 2 + 0), SphereNoise(params.seed * 2 + 1),
                                              SphereNoise(params.seed * 2 + 0x5eed)})) {}
PlanetField::~PlanetField() = default;
PlanetField::PlanetField(PlanetField&&) noexcept = default;

double PlanetField::landness(double latDeg, double lonDeg) const {
  return noises_->continents.fbm(unitVector(latDeg, lonDeg), 1.6, 7) - 0.01;
}

double PlanetField::heightM(double latDeg, double lonDeg, int detailOctaves, bool* isLand) const {
  const glm::dvec3 q = unitVector(latDeg, lonDeg);
  const double scale = params_.highestM;
  // Continents: large, smooth shapes; the coast where they cross 0.
  const double land = noises_->continents.fbm(q, 1.6, 7) - 0.01;
  // Mountain ranges: ridged noise, strongest inland.
  const double ridge = 1.0 - std::abs(noises_->mountains.fbm(q, 3.0, 6) * 2.0);
  const double inland = std::clamp(land / 0.15, 0.0, 1.0);
  double height = land > 0.0 ? scale * (0.25 * land + 0.55 * inland * ridge * ridge * ridge)
                             : scale * 1.6 * std::max(land, -0.45) - 200.0;
  if (detailOctaves > 0 && land > 0.0) {
    // Ridged detail from 50 km wavelength (frequency 128 on the unit sphere) down, rougher than
    // the planet's own octaves (gain 0.62), fading in from the coast and strongest in the ranges.
    const double d = 1.0 - std::abs(noises_->detail.fbm(q, 128.0, detailOctaves, 0.62) * 2.0);
    height += scale * (0.06 + 0.25 * inland * (0.3 + ridge * ridge)) * (d - 0.3) * std::min(1.0, land / 0.02);
  }
  if (isLand) *isLand = land > 0.0;
  return params_.plateau ? blendPlateau(*params_.plateau, q, height) : height;
}

HeightGrid generatePlanet(const PlanetParams& params) {
  int columns = std::clamp(params.columns, kMinPlanetColumns, kMaxPlanetColumns);
  columns += columns % 2;
  const int rows = columns / 2;
  const double step = 360.0 / columns;
  HeightGrid grid(columns, rows);
  const PlanetField field(params);
  tbb::parallel_for(0, rows, [&](int j) {
    const double latDeg = 90.0 - (j + 0.5) * step;
    for (int i = 0; i < columns; ++i) {
      grid.at(i, j) = float(field.heightM(latDeg, -180.0 + (i + 0.5) * step));
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
