// tellus info: what a DEM is (size, CRS, spacing, heights, voids) and what the GL context offers.
#include <fmt/format.h>

#include "cli_support.hpp"
#include "tellus/gl/gl_info.hpp"

namespace tellus::cli {
namespace {

struct InfoOptions {
  DemInputOptions dem;
  bool gl = false;
  std::string context = "headless";
};

void printDemInfo(const HeightGrid& grid, const DemInputOptions& options) {
  const HeightRange range = grid.heightRange();
  const auto row = [](std::string_view name, const std::string& value) {
    fmt::print("{:<18}{}\n", fmt::format("{}:", name), value);
  };
  row("input", options.inputs.size() == 1
                   ? options.inputs[0]
                   : fmt::format("{} files (mosaic)", options.inputs.size()));
  row("size", fmt::format("{} x {} samples", grid.width, grid.height));
  std::string crs = grid.georef.crsName.empty() ? "none" : grid.georef.crsName;
  if (!grid.georef.crsName.empty())
    crs += grid.georef.isGeographic ? " (geographic)" : " (projected)";
  row("CRS", crs);
  if (grid.georef.hasGeoTransform) {
    const auto& gt = grid.georef.geoTransform;
    row("geotransform",
        fmt::format("origin ({:.6f}, {:.6f}), pixel {:.9g} x {:.9g}", gt[0], gt[3], gt[1], gt[5]));
  }
  row("sample spacing",
      fmt::format("{:.3f} m (east-west) x {:.3f} m (north-south)", grid.spacingXM, grid.spacingYM));
  row("extent", fmt::format("{:.2f} km x {:.2f} km", (grid.width - 1) * grid.spacingXM / 1000.0,
                            (grid.height - 1) * grid.spacingYM / 1000.0));
  row("heights", fmt::format("min {:.2f} m, max {:.2f} m", range.minM, range.maxM));
  row("voids", grid.filledVoidCount == 0
                   ? std::string("none")
                   : fmt::format("{} (filled by interpolation)", grid.filledVoidCount));
}

}  // namespace

Command addInfoCommand(CLI::App& app) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* sub = app.add_subcommand("info", "Describe DEM files and/or the OpenGL context");
  addDemInputOptions(sub, options->dem, false);
  sub->add_flag("--gl", options->gl, "Print the OpenGL vendor, renderer, version and limits");
  sub->add_option("--context", options->context, "OpenGL context: headless (EGL) or window (GLFW)")
      ->check(CLI::IsMember({"headless", "window"}));
  return {sub, [options, sub]() -> int {
            if (options->dem.inputs.empty() && !options->gl) {
              return fail(makeError("info: give DEM files and/or --gl (see tellus info --help)"));
            }
            if (!options->dem.inputs.empty()) {
              Result<HeightGrid> grid = loadDemInputs(options->dem);
              if (!grid) return fail(grid.error());
              printDemInfo(grid.value(), options->dem);
            }
            if (options->gl) {
              Result<std::unique_ptr<gl::GlContext>> context = createContext(options->context);
              if (!context) return fail(context.error());
              if (!options->dem.inputs.empty()) fmt::print("\n");
              fmt::print("{}", gl::formatGlInfo(gl::queryGlInfo(), context.value()->description()));
            }
            (void)sub;
            return 0;
          }};
}

}  // namespace tellus::cli
