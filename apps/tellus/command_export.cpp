// tellus export: one level of a store as a GeoTIFF that other GIS tools open.
#include <fmt/format.h>

#include "cli_numbers.hpp"
#include "cli_support.hpp"
#include "tellus/core/atomic_output.hpp"
#include "tellus/dem/geotiff_writer.hpp"

namespace tellus::cli {
namespace {
struct ExportOptions {
  std::string store;
  std::string output;
  int level = 0;
};
}  // namespace

Command addExportCommand(CLI::App& app) {
  auto o = std::make_shared<ExportOptions>();
  CLI::App* sub = app.add_subcommand("export", "Write one level of a store as a GeoTIFF");
  sub->add_option("store", o->store, "The tile store (.tstore)")->required();
  sub->add_option("-o,--output", o->output, "The GeoTIFF to write")->required();
  sub->add_option("--level", o->level, "Pyramid level (0 = full resolution)")
      ->check(integerIn(0, kMaxStoreLevel));
  return {sub,
          [o]() -> int {
            DemInputOptions input;
            input.inputs = {o->store};
            input.storeLevel = o->level;
            if (!isTileStoreInput(input.inputs)) {
              return fail(makeError("'{}' is not a tile store (make one with tellus build)",
                                    o->store));
            }
            Result<HeightGrid> grid = loadDemInputs(input);  // checks the memory it needs
            if (!grid) return fail(grid.error());
            if (Status s = writeGeoTiff(grid.value(), o->output); !s) return fail(s.error());
            fmt::print("{}: level {} of {}, {} x {} samples\n", o->output, o->level, o->store,
                       grid->width, grid->height);
            return 0;
          },
          [o] { return CommandFiles{{o->store}, {o->output}, {}}; }};
}

}  // namespace tellus::cli
