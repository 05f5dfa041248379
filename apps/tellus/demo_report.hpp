#pragma once
// The pages of `tellus demo`: index.html and index.md, from what the demo rendered and the
// report of its benchmark (bench/bench.json).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "tellus/core/camera.hpp"
#include "tellus/core/geo_camera.hpp"
#include "tellus/core/result.hpp"
#include "tellus/render/terrain_renderer.hpp"

namespace tellus::cli {

struct DemoImage {
  std::string file;   // relative to the demo folder
  std::string title;  // a caption
  std::string algo;   // the renderer that drew it
  Camera camera;
  FrameStats stats;
  double milliseconds = 0.0;  // wall time of the still, upload and read-back included
  std::string errorShading;   // what its error shading shows (RendererFamily::errorShading)
};

// A flythrough (render --path ... --video).
struct DemoVideo {
  std::string file;     // relative to the demo folder
  std::string title;    // a caption
  std::string command;  // the command line that makes it again
};

// A still on the globe.
struct DemoGlobeImage {
  std::string file;   // relative to the demo folder
  std::string title;  // a caption
  std::string algo;   // the renderer that drew it
  GeoCamera camera;
  FrameStats stats;
  double milliseconds = 0.0;
};

// The globe section: a procedural planet with the terrain on it, its stills and a benchmark.
struct DemoGlobe {
  std::string summary;  // the planet and the global store, a sentence or two
  std::vector<DemoGlobeImage> images;
  std::string benchFolder;   // relative: the bench plots, bench.json inside
  std::string benchCommand;  // the command line that reproduces the benchmark
  std::vector<DemoVideo> videos;  // the descent from orbit
};

// The stack-terrain section (seed 003): a generated terrain with caves, overhangs and arches
// drawn by stacks-full.
struct DemoStacks {
  std::string summary;  // the terrain, its stacks and mesh, a sentence or two
  std::vector<DemoImage> images;
};

struct DemoPage {
  std::string terrainSummary;  // one sentence on the generated terrain
  std::string storeSummary;    // one sentence on the store built from it
  std::string glRenderer;
  std::vector<DemoVideo> videos;  // flythroughs, shown first
  // The same view drawn by each compared renderer, lit and with its screen-space error, in
  // pairs (lit, error) in renderer order.
  std::vector<DemoImage> comparison;
  std::vector<DemoImage> gallery;  // further views
  std::string benchFolder;         // relative: the bench plots, bench.json inside
  std::string benchCommand;        // the command line that reproduces the benchmark
  std::optional<DemoStacks> stacks;  // written after the gallery when set
  std::optional<DemoGlobe> globe;   // written after the stacks when set
};

// Writes dir/index.html and dir/index.md, reading dir/<benchFolder>/bench.json (and the globe's
// bench.json when there is a globe section).
Status writeDemoPages(const std::filesystem::path& dir, const DemoPage& page);

// The benchmark table of a bench.json report: one row per renderer with frame ms, CPU and GPU
// ms, triangles (medians), SSE p95/p99, crack pixels and popping p99 over the path. Markdown.
std::string benchTableMarkdown(const nlohmann::json& report);

}  // namespace tellus::cli
