// tellus export: one level of a store as a GeoTIFF that other GIS tools open.
#include <fmt/format.h>

#include "cli_numbers.hpp"
#include "cli_support.hpp"
#include "global_store_cli.hpp"
#include "tellus/core/atomic_output.hpp"
#include "tellus/dem/geotiff_writer.hpp"

namespace tellus::cli {
namespace {
struct ExportOptions {
  std::string store;
  std::string output;
  int level = 0;
  int depth = -1;
  std::string region;
};

// A global store: one depth over a region (default the whole globe at the deepest depth that
// fits the sample budget).
int exportGlobal(const ExportOptions& o) {
  Result<std::shared_ptr<GlobalStore>> store = GlobalStore::open(o.store);
  if (!store) return fail(store.error());
  GlobalRegionRequest request;
  if (o.depth >= 0) request.depth = o.depth;
  if (!o.region.empty()) {
    Result<GeoBounds> region = parseGeoBounds(o.region);
    if (!region) return fail(region.error());
    request.region = region.value();
  }
  Result<GlobalRegion> chosen = chooseGlobalRegion(*store.value(), request);
  if (!chosen) return fail(chosen.error());
  Result<HeightGrid> grid = loadGlobalStoreRegion(*store.value(), request);
  if (!grid) return fail(grid.error());
  if (Status s = writeGeoTiff(grid.value(), o.output); !s) return fail(s.error());
  fmt::print("{}: depth {} of {}, {} x {} samples\n", o.output, chosen->depth, o.store,
             grid->width, grid->height);
  return 0;
}
}  // namespace

Command addExportCommand(CLI::App& app) {
  auto o = std::make_shared<ExportOptions>();
  CLI::App* sub = app.add_subcommand("export", "Write one level of a store as a GeoTIFF");
  sub->add_option("store", o->store, "The tile store (.tstore)")->required();
  sub->add_option("-o,--output", o->output, "The GeoTIFF to write")->required();
  sub->add_option("--level", o->level, "Pyramid level (0 = full resolution)")
      ->check(integerIn(0, kMaxStoreLevel));
  sub->add_option("--depth", o->depth,
                  "Global stores: the depth to export (default: the deepest that fits)")
      ->check(integerIn(0, GlobalTiling::kMaxDepth));
  sub->add_option("--region", o->region,
                  "Global stores: WEST,SOUTH,EAST,NORTH degrees (default: the whole globe)");
  return {sub,
          [o]() -> int {
            if (isTileStoreInput({o->store}) && isGlobalStore(o->store)) return exportGlobal(*o);
            if (o->depth >= 0 || !o->region.empty()) {
              return fail(makeError("--depth and --region apply to global stores"));
            }
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
