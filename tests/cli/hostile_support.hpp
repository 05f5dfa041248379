#pragma once
// What the hostile-input suites share (hostile_input_test.cpp, hostile_surfaces_test.cpp):
// running tellus under a time limit, judging a refusal, small fixtures.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "cli/run_tellus.hpp"

namespace tellus {

// Runs tellus with a time limit: a hang is a failure (exit status 124/137), not a stuck suite.
RunResult runBounded(const std::string& arguments, int seconds = 60);

// A clean refusal: a status from 1 to 127 (128+ is a signal through the shell, 124/137 a
// timeout), the message part, one line of tellus' own or CLI11's two, no abort or crash.
void expectRefused(const RunResult& result, const std::string& messagePart, const std::string& what);

std::vector<std::string> filesIn(const std::filesystem::path& dir);
std::string contentOf(const std::filesystem::path& file);
void writeText(const std::filesystem::path& file, const std::string& text);

// A small Int16 GeoTIFF (33 x 33) with the given geotransform in EPSG:4326 (no CRS when epsg
// is 0).
void writeSmallGeoTiff(const std::filesystem::path& file, const std::array<double, 6>& gt, int epsg = 4326);
// A 100000 x 100000 Int16 GeoTIFF in EPSG:4326 at 126 E 38 N, sparse (a few KiB on disk).
void writeSparseHugeGeoTiff(const std::filesystem::path& file);
inline const std::array<double, 6> kGoodGeoTransform = {127.0, 0.001, 0.0, 37.5, 0.0, -0.001};

// A generated terrain (129 x 129) and a store of it with several levels.
struct SmallTerrain {
  std::filesystem::path dem, store;
};
SmallTerrain makeSmallTerrain(const std::filesystem::path& dir);

}  // namespace tellus
