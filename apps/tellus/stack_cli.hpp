#pragma once
// The material-stack terrain (seed 003) on the command line: .tstack files in tellus info and
// tellus verify.
#include <string>

#include "cli_support.hpp"

namespace tellus::cli {

// tellus stacks build DEM... -o t.tstack: a DEM made material stacks with caves, overhangs and
// arches, its level pyramid written to a .tstack; tellus stacks preset -o t.tstack: the seed's
// 4 km x 8 km test terrain (2048 x 4096 stacks at 2 m, up to about 768 m) from a generated one.
Command addStacksCommand(CLI::App& app);

// True for a path ending in .tstack.
bool isStackFile(const std::string& path);
// tellus info FILE.tstack: levels, stacks, layers, memory against the dense voxel grid.
int printStackInfo(const std::string& path);
// tellus verify FILE.tstack: reads and checks every level; 0 only when all are good.
int verifyStackFile(const std::string& path);

}  // namespace tellus::cli
