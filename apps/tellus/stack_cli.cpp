#include "stack_cli.hpp"

#include <algorithm>
#include <chrono>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "cli_numbers.hpp"
#include "tellus/core/atomic_output.hpp"
#include "tellus/dem/terrain_generator.hpp"
#include "tellus/formats/stacks/stack_aggregation.hpp"
#include "tellus/formats/stacks/stack_file.hpp"
#include "tellus/formats/stacks/stack_generator.hpp"
#include "tellus/formats/stacks/stack_surface.hpp"

namespace tellus::cli {

bool isStackFile(const std::string& path) {
  return path.size() > 7 && path.substr(path.size() - 7) == ".tstack";
}

Result<LoadedStacks> loadStacks(const std::string& path, bool imagery) {
  GeoReference georef;
  Result<std::vector<StackTerrain>> levels = readStackFile(path, &georef);
  if (!levels) return levels.error();
  if (imagery && georef.crsWkt.empty()) {
    return makeError("'{}' has no georeference (a generated terrain, or a .tstack written before "
                     "Tellus kept one): --imagery needs one built by 'tellus stacks build' from a "
                     "georeferenced DEM",
                     path);
  }
  LoadedStacks loaded;
  loaded.surface = topSurfaceGrid(levels->front());
  loaded.surface.georef = std::move(georef);
  loaded.levels = std::move(levels.value());
  return loaded;
}

int printStackInfo(const std::string& path) {
  Result<std::vector<StackTerrain>> levels = readStackFile(path);
  if (!levels) return fail(levels.error());
  Result<StackFileSummary> summary = summariseStackFile(path);
  if (!summary) return fail(summary.error());
  const StackTerrain& finest = levels->front();
  const StackFileSummary& s = summary.value();
  fmt::print("{}: material stacks, {} x {} stacks at {:.3g} m ({:.3f} x {:.3f} km), up to {:.1f} m\n",
             path, s.width, s.height, s.spacingM, s.width * s.spacingM / 1000.0,
             s.height * s.spacingM / 1000.0, finest.topM());
  fmt::print("  {} levels, {} layers ({:.2f} a stack at level 0)\n", s.levels, s.layers,
             double(finest.layerCount()) / (double(s.width) * s.height));
  if (s.georef.crsWkt.empty()) {
    fmt::print("  no georeference (imagery cannot be draped on it)\n");
  } else {
    const std::array<double, 6>& g = s.georef.geoTransform;
    fmt::print("  georeferenced: {}, the north-west corner at ({:.10g}, {:.10g}), {:.6g} x {:.6g} a stack\n",
               s.georef.crsName.empty() ? "a CRS without a name" : s.georef.crsName, g[0], g[3], g[1], -g[5]);
  }
  const std::uint64_t voxels = finest.denseVoxelBytes(s.spacingM);
  fmt::print("  memory {:.1f} MiB (all levels), file {:.1f} MiB; as dense voxels of {:.3g} m (one "
             "byte each): {:.1f} MiB at level 0\n",
             double(s.memoryBytes) / double(1 << 20), double(s.fileBytes) / double(1 << 20),
             s.spacingM, double(voxels) / double(1 << 20));
  for (int k = 0; k < s.levels; ++k) {
    const StackTerrain& t = (*levels)[std::size_t(k)];
    fmt::print("  level {}: {} x {} stacks at {:.4g} m, {} layers\n", k, t.width(), t.height(),
               t.spacingM(), t.layerCount());
  }
  return 0;
}

Result<StackTerrain> readStackLevel(const std::string& path, int level) {
  Result<std::vector<StackTerrain>> levels = readStackFile(path);
  if (!levels) return levels.error();
  if (level < 0 || level >= int(levels->size())) {
    return makeError("{} has levels 0 to {}, not {}", path, levels->size() - 1, level);
  }
  return std::move((*levels)[std::size_t(level)]);
}

int verifyStackFile(const std::string& path) {
  Result<std::vector<StackTerrain>> levels = readStackFile(path);
  if (!levels) return fail(levels.error());
  if (Status pyramid = verifyStackPyramid(levels.value()); !pyramid) {
    return fail(makeError("'{}': {}", path, pyramid.error().message));
  }
  std::uint64_t layers = 0;
  for (const StackTerrain& level : levels.value()) layers += level.layerCount();
  fmt::print("{}: all {} levels good ({} layers checked; every level the aggregation of the one "
             "below)\n",
             path, levels->size(), layers);
  return 0;
}

namespace {

struct StacksOptions {
  DemInputOptions dem;
  std::string output;
  StackGeneratorOptions generator;
};

// Stacks from `grid`, their pyramid, the file; reports sizes against dense voxels.
int writeStacks(const HeightGrid& grid, const StacksOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  const HeightGrid square = squareCells(grid);
  if (square.width != grid.width || square.height != grid.height) {
    spdlog::info("resampled {} x {} samples ({:.1f} x {:.1f} m) to {} x {} square cells of {:.1f} m",
                 grid.width, grid.height, grid.spacingXM, grid.spacingYM, square.width,
                 square.height, square.spacingXM);
  }
  StackFeatureReport features;
  Result<StackTerrain> stacks = generateStacks(square, o.generator, &features);
  if (!stacks) return fail(stacks.error());
  if (o.generator.features.arches) {
    const auto widest = std::max_element(
        features.arches.begin(), features.arches.end(),
        [](const StackArch& a, const StackArch& b) { return a.openingM < b.openingM; });
    if (widest == features.arches.end()) {
      spdlog::info("no arch: no valley found to span (the terrain may be too gentle)");
    } else {
      spdlog::info("{} arch{}, the tallest from stack ({}, {}) to ({}, {}) over an opening of "
                   "{:.1f} m",
                   features.arches.size(), features.arches.size() == 1 ? "" : "es", widest->x0,
                   widest->y0, widest->x1, widest->y1, widest->openingM);
    }
  }
  const std::uint64_t voxels = stacks->denseVoxelBytes(stacks->spacingM());
  const std::vector<StackTerrain> levels = buildStackPyramid(std::move(stacks.value()));
  if (Status written = writeStackFile(o.output, levels, square.georef); !written) return fail(written.error());
  std::uint64_t bytes = 0, layers = 0;
  for (const StackTerrain& t : levels) {
    bytes += t.bytes();
    layers += t.layerCount();
  }
  std::error_code ec;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  spdlog::info("wrote {} ({} x {} stacks at {:.3g} m, {} levels, {} layers; {:.1f} MiB in memory, "
               "{:.1f} MiB on disk; as one-byte voxels of {:.3g} m: {:.1f} MiB) in {:.1f} s",
               o.output, levels.front().width(), levels.front().height(), levels.front().spacingM(),
               levels.size(), layers, double(bytes) / double(1 << 20),
               double(std::filesystem::file_size(o.output, ec)) / double(1 << 20),
               levels.front().spacingM(), double(voxels) / double(1 << 20), seconds);
  return 0;
}

void addGeneratorOptions(CLI::App* sub, StacksOptions& o) {
  sub->add_option("-o,--output", o.output, "Output stack file (.tstack)")->required();
  addSeedOption(sub, o.generator.seed);
  sub->add_option_function<std::vector<std::string>>(
         "--features",
         [&o](const std::vector<std::string>& names) {
           o.generator.features = {false, false, false};
           for (const std::string& name : names) {
             if (name == "caves") o.generator.features.caves = true;
             if (name == "overhangs") o.generator.features.overhangs = true;
             if (name == "arches") o.generator.features.arches = true;
           }
         },
         "3D features to add: caves, overhangs, arches, or none (default: all three)")
      ->delimiter(',')
      ->check(CLI::IsMember({"caves", "overhangs", "arches", "none"}));
}

}  // namespace

Command addStacksCommand(CLI::App& app) {
  auto options = std::make_shared<StacksOptions>();
  auto preset = std::make_shared<StacksOptions>();
  CLI::App* sub = app.add_subcommand(
      "stacks", "Material-stack terrain (seed 003): build .tstack files, quadrangulate them");
  sub->require_subcommand(1);
  CLI::App* build = sub->add_subcommand("build", "A DEM as material stacks with caves, overhangs and arches");
  addDemInputOptions(build, options->dem, true);
  addGeneratorOptions(build, *options);
  CLI::App* seedPreset = sub->add_subcommand(
      "preset", "The seed's test terrain: 4 km x 8 km, 2048 x 4096 stacks at 2 m, up to ~768 m");
  addGeneratorOptions(seedPreset, *preset);
  auto quadOptions = std::make_shared<StacksQuadOptions>();
  CLI::App* quad = sub->add_subcommand(
      "quad", "Quadrangulate a .tstack level on the CPU reference and the GPU: times per stage and node");
  addStacksQuadOptions(quad, *quadOptions);
  auto editOptions = std::make_shared<StacksEditOptions>();
  CLI::App* edit = sub->add_subcommand(
      "edit", "Add or remove a sphere of material on the finest level; the levels above follow");
  addStacksEditOptions(edit, *editOptions);
  return {sub,
          [options, preset, build, quad, quadOptions, edit, editOptions]() -> int {
            if (quad->parsed()) return runStacksQuad(*quadOptions);
            if (edit->parsed()) return runStacksEdit(*editOptions);
            const bool building = build->parsed();
            const StacksOptions& o = building ? *options : *preset;
            if (!isStackFile(o.output)) {
              return fail(makeError("the output '{}' must end in .tstack", o.output));
            }
            if (Status writable = checkOutputWritable(o.output); !writable) return fail(writable.error());
            if (building) {
              Result<HeightGrid> grid = loadDemInputs(o.dem, 64.0);
              if (!grid) return fail(grid.error());
              return writeStacks(grid.value(), o);
            }
            TerrainParams params;
            params.size = 4097;
            params.seed = o.generator.seed;
            params.spacingM = 2.0;
            params.reliefM = 768.0;
            HeightGrid square = generateTerrain(params);
            HeightGrid crop(2048, 4096);
            crop.spacingXM = crop.spacingYM = 2.0;
            for (int y = 0; y < 4096; ++y) {
              for (int x = 0; x < 2048; ++x) crop.at(x, y) = square.at(x, y);
            }
            return writeStacks(crop, o);
          },
          [options, preset, build, quad, quadOptions, edit, editOptions] {
            if (edit->parsed()) {
              // In place: the file is read, then replaced atomically (not an input to protect).
              const StacksEditOptions& e = *editOptions;
              if (e.output.empty()) return CommandFiles{{}, {e.input}, {}};
              return CommandFiles{{e.input}, {e.output}, {}};
            }
            if (quad->parsed()) {
              std::vector<std::string> written;
              if (!quadOptions->json.empty()) written.push_back(quadOptions->json);
              return CommandFiles{{quadOptions->input}, written, {}};
            }
            const StacksOptions& o = build->parsed() ? *options : *preset;
            return CommandFiles{build->parsed() ? o.dem.inputs : std::vector<std::string>{}, {o.output}, {}};
          }};
}

}  // namespace tellus::cli
