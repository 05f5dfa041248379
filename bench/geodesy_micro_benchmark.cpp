// Google Benchmark micro-benchmarks of the per-vertex geodesy path: geodetic <-> ECEF (this
// project's code) beside PROJ's +proj=cart on the same points, and the EGM96 geoid lookup.
// Items per second = points converted. Run: build/release/bench/tellus_micro_benchmarks
// --benchmark_filter=Geo
#include <benchmark/benchmark.h>

#include <filesystem>
#include <random>
#include <vector>

#include <proj.h>

#include "tellus/core/geodesy.hpp"
#include "tellus/dem/geoid.hpp"

namespace tellus {
namespace {

constexpr std::size_t kPoints = 4096;

const std::vector<wgs84::Geodetic>& randomPoints() {
  static const std::vector<wgs84::Geodetic> points = [] {
    std::mt19937_64 random(5);
    std::uniform_real_distribution<double> lat(-90.0, 90.0), lon(-180.0, 180.0),
        height(-500.0, 9000.0);
    std::vector<wgs84::Geodetic> made;
    for (std::size_t i = 0; i < kPoints; ++i) {
      made.push_back({lat(random) * wgs84::kDegree, lon(random) * wgs84::kDegree, height(random)});
    }
    return made;
  }();
  return points;
}

const std::vector<glm::dvec3>& randomEcef() {
  static const std::vector<glm::dvec3> points = [] {
    std::vector<glm::dvec3> made;
    for (const wgs84::Geodetic& p : randomPoints()) made.push_back(wgs84::geodeticToEcef(p));
    return made;
  }();
  return points;
}

void BM_GeodeticToEcef(benchmark::State& state) {
  const auto& points = randomPoints();
  for (auto _ : state) {
    for (const wgs84::Geodetic& p : points) benchmark::DoNotOptimize(wgs84::geodeticToEcef(p));
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(points.size()));
}
BENCHMARK(BM_GeodeticToEcef);

void BM_EcefToGeodetic(benchmark::State& state) {
  const auto& points = randomEcef();
  for (auto _ : state) {
    for (const glm::dvec3& p : points) benchmark::DoNotOptimize(wgs84::ecefToGeodetic(p));
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(points.size()));
}
BENCHMARK(BM_EcefToGeodetic);

// PROJ on the same points, one call per point (proj_trans) and in one batch (proj_trans_array).
void projCart(benchmark::State& state, PJ_DIRECTION direction, bool batch) {
  PJ_CONTEXT* context = proj_context_create();
  PJ* cart = proj_create(context, "+proj=cart +ellps=WGS84");
  std::vector<PJ_COORD> input;
  for (const wgs84::Geodetic& p : randomPoints()) {
    input.push_back(proj_coord(p.lonRad, p.latRad, p.heightM, 0.0));
  }
  if (direction == PJ_INV) {
    for (PJ_COORD& c : input) c = proj_trans(cart, PJ_FWD, c);
  }
  std::vector<PJ_COORD> work = input;
  for (auto _ : state) {
    if (batch) {
      work = input;
      proj_trans_array(cart, direction, work.size(), work.data());
      benchmark::DoNotOptimize(work.data());
    } else {
      for (const PJ_COORD& c : input) benchmark::DoNotOptimize(proj_trans(cart, direction, c));
    }
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(input.size()));
  proj_destroy(cart);
  proj_context_destroy(context);
}
BENCHMARK_CAPTURE(projCart, ProjCartForward, PJ_FWD, false);
BENCHMARK_CAPTURE(projCart, ProjCartForwardBatch, PJ_FWD, true);
BENCHMARK_CAPTURE(projCart, ProjCartInverse, PJ_INV, false);

void BM_GeoidUndulation(benchmark::State& state) {
  static const Result<Geoid> geoid =
      Geoid::load(std::filesystem::path(TELLUS_SHARED_DATA_DIR) / "egm96-geoid/egm96_15.gtx");
  if (!geoid) {
    state.SkipWithError("../shared/data/egm96-geoid is absent");
    return;
  }
  const auto& points = randomPoints();
  for (auto _ : state) {
    for (const wgs84::Geodetic& p : points) {
      benchmark::DoNotOptimize(
          geoid->undulationM(p.latRad / wgs84::kDegree, p.lonRad / wgs84::kDegree));
    }
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(points.size()));
}
BENCHMARK(BM_GeoidUndulation);

}  // namespace
}  // namespace tellus
