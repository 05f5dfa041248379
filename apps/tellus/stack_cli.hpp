#pragma once
// The material-stack terrain (seed 003) on the command line: .tstack files in tellus info and
// tellus verify.
#include <string>

#include "cli_support.hpp"
#include "tellus/render/stacks/stacks_full_renderer.hpp"
#include "tellus/formats/stacks/quadrangulation.hpp"
#include "tellus/eval/path_benchmark.hpp"
#include "tellus/formats/stacks/stack_edit.hpp"
#include "tellus/formats/stacks/stack_file.hpp"

namespace tellus::cli {

// tellus stacks build DEM... -o t.tstack: a DEM made material stacks with caves, overhangs and
// arches, its level pyramid written to a .tstack; tellus stacks preset -o t.tstack: the seed's
// 4 km x 8 km test terrain (2048 x 4096 stacks at 2 m, up to about 768 m) from a generated one.
Command addStacksCommand(CLI::App& app);

// tellus stacks quad t.tstack: the quadrangulation pipeline over a level on the CPU reference
// and the GPU, per-stage times per node, nodes per second, the mesh checks (stack_quad_cli.cpp).
struct StacksQuadOptions {
  std::string input;
  int level = 0;
  QuadParams params;
  std::string filter = "gauss";
  double cellM = 0.0;  // 0: the stacks' spacing
  std::size_t nodes = 0;
  int batch = 256;
  bool noGpu = false, noCpu = false;
  std::string json;
};
// One level of a .tstack (0: finest); errors name the file and the levels it has.
Result<StackTerrain> readStackLevel(const std::string& path, int level);


void addStacksQuadOptions(CLI::App* quad, StacksQuadOptions& options);
int runStacksQuad(StacksQuadOptions options);

// tellus stacks edit t.tstack --sphere x,y,z,r --add rock|--remove [-o out.tstack]: a sphere
// of material added or removed on the finest level, the levels above re-aggregated, the file
// replaced atomically (stack_edit_cli.cpp).
struct StacksEditOptions {
  std::string input, output;  // output empty: the input, replaced
  std::string sphere;         // x,y,z,r metres (x east, y north of the south-west stack)
  std::string add;            // material name or id; empty with remove
  bool remove = false;
};
void addStacksEditOptions(CLI::App* edit, StacksEditOptions& options);
int runStacksEdit(const StacksEditOptions& options);
// The material of a name (rock, soil, grass) or an id 1..255; errors list the names.
Result<StackMaterial> parseStackMaterial(const std::string& text);

// True for a path ending in .tstack.
bool isStackFile(const std::string& path);
// A .tstack as render, bench and view draw it: its levels, and the top surface of the finest
// (named views, paths over the ground), georeferenced as the file says, so that --imagery is
// placed by it. With `imagery`, a file without a georeference is refused (a generated terrain).
struct LoadedStacks {
  std::vector<StackTerrain> levels;
  HeightGrid surface;
};
Result<LoadedStacks> loadStacks(const std::string& path, bool imagery);
// tellus info FILE.tstack: levels, stacks, layers, memory against the dense voxel grid.
int printStackInfo(const std::string& path);
// tellus verify FILE.tstack: reads and checks every level; 0 only when all are good.
int verifyStackFile(const std::string& path);

// tellus bench --stack-edits N (stack_edit_bench.cpp): N strokes planned along the path, each
// at the first solid point under a cursor wandering over the middle of the frame, 3 stacks in
// radius, alternately carving and adding rock or soil (fewer when a ray finds no ground).
std::vector<ScriptedStackEdit> planBenchStrokes(std::vector<StackTerrain> pyramid,
                                                const std::vector<Camera>& cameras,
                                                const Aabb& bounds, int count);
// stacks-full along `cameras` with the strokes applied before their frames: made again from
// the edited stacks after each stroke (the ground truth of an edit benchmark).
Result<PathRun> runEditedGroundTruth(std::vector<StackTerrain> pyramid,
                                     const std::vector<ScriptedStackEdit>& strokes,
                                     const std::vector<Camera>& cameras, const Aabb& bounds,
                                     const PathRunOptions& options,
                                     const RendererSettings& settings);
// What the octree renderer's strokes cost: per stroke the edit's milliseconds, the meshes it
// dropped and the frame that drew the result.
struct StrokeTimings {
  std::vector<double> editMs, meshes;
  std::vector<double> stacksMs, levelsMs, uploadMs;  // editMs in parts (StacksEditReport)
  std::vector<int> frames;
  void report(const PathRun& run) const;  // one log line
};
// PathRunOptions::beforeFrame for the octree renderer (`renderer` must be a
// StacksLodRenderer): applies the strokes due and records their timings.
std::function<void(int)> applyStrokesBeforeFrames(TerrainRenderer& renderer,
                                                  const std::vector<ScriptedStackEdit>& strokes,
                                                  StrokeTimings& timings);

}  // namespace tellus::cli
