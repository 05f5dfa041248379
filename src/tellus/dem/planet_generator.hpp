#pragma once
// A procedural planet: a deterministic latitude/longitude height grid of a whole Earth-sized
// world (ocean floors, continents, mountain ranges), the global source of `tellus demo`'s globe
// when no real data is at hand. GL-free.
//
// Heights come from fractal gradient noise evaluated on the unit sphere, not on the lat/lon
// rectangle: each sample's direction q is projected on the three coordinate planes and the
// three noises are blended by q's components (to the 4th power), so the field is continuous
// across the antimeridian and has no pinch at the poles.
#include <cstdint>
#include <memory>
#include <optional>

#include "tellus/dem/height_grid.hpp"

namespace tellus {

// Land at a given height around a point: where a finer source is put on the planet (tellus
// demo puts its terrain there), so that it does not stand on the sea floor. Within radiusDeg
// (angular distance) the planet is heightM; beyond, it blends back into the noise over as much
// again (smoothstep).
struct PlanetPlateau {
  double latDeg = 0.0, lonDeg = 0.0;
  double radiusDeg = 1.0;
  double heightM = 500.0;
};

struct PlanetParams {
  int columns = 2160;         // samples around the equator (2160: 10 arc-minutes); rows = columns / 2
  std::uint64_t seed = 1;
  double highestM = 6000.0;   // roughly the highest peaks; the deepest sea floor is about as deep
  std::optional<PlanetPlateau> plateau;
};

inline constexpr int kMinPlanetColumns = 16, kMaxPlanetColumns = 1 << 15;

// The planet's heights at any point: the field generatePlanet() samples. With `detailOctaves`
// > 0, relief finer than the planet's 10' (ridged fractal noise from 50 km wavelength down, the
// octave k's amplitude 0.62^k of the first, on land: hills of about a twentieth of `highestM` on
// the plains, ranges of about a third inland) for grids as fine as SRTM's; 0 gives exactly
// generatePlanet()'s heights. Thread-safe: const after construction.
class PlanetField {
 public:
  explicit PlanetField(const PlanetParams& params);
  ~PlanetField();
  PlanetField(PlanetField&&) noexcept;
  // Metres at (latDeg, lonDeg); `isLand` (optional) says whether the point is above the
  // continents' coastline (the sea floor's heights are below 0 there).
  double heightM(double latDeg, double lonDeg, int detailOctaves = 0, bool* isLand = nullptr) const;
  // The continents' shape alone (cheap: > 0 on land), for deciding where land is.
  double landness(double latDeg, double lonDeg) const;

 private:
  struct Noises;
  PlanetParams params_;
  std::unique_ptr<Noises> noises_;
};

// The grid: columns x columns/2 pixel-is-area cells covering -180..180 E and -90..90 N exactly
// (sample centres half a cell inside), georeferenced as WGS 84 latitude/longitude, heights in
// metres. About a third of the surface is land. `columns` is clamped into the range above and
// rounded up to even.
HeightGrid generatePlanet(const PlanetParams& params);

}  // namespace tellus
