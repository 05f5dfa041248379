// tellus stacks edit: a sphere of material added to or removed from a .tstack's finest level,
// the MipMap above re-aggregated where it changed, written atomically (stacks/stack_edit.hpp).
#include <array>
#include <charconv>
#include <chrono>

#include <spdlog/spdlog.h>

#include "stack_cli.hpp"
#include "tellus/core/number_fields.hpp"
#include "tellus/formats/stacks/stack_edit.hpp"
#include "tellus/formats/stacks/stack_file.hpp"
#include "tellus/formats/stacks/stack_generator.hpp"

namespace tellus::cli {

Result<StackMaterial> parseStackMaterial(const std::string& text) {
  if (text == "rock") return kStackRock;
  if (text == "soil") return kStackSoil;
  if (text == "grass") return kStackGrass;
  int id = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), id);
  if (!text.empty() && ec == std::errc() && end == text.data() + text.size() && id >= 1 && id <= 255) {
    return StackMaterial(id);
  }
  return makeError("unknown material '{}': give rock, soil, grass or an id from 1 to 255", text);
}

void addStacksEditOptions(CLI::App* edit, StacksEditOptions& o) {
  edit->add_option("input", o.input, "The .tstack to edit")->required();
  edit->add_option("--sphere", o.sphere,
                   "x,y,z,r: the sphere's centre (metres east and north of the south-west stack, "
                   "and above the terrain's base) and radius")
      ->required();
  auto* add = edit->add_option("--add", o.add, "Fill the sphere with this material: rock, soil, grass or an id 1..255");
  auto* remove = edit->add_flag("--remove", o.remove, "Empty the sphere (carve)");
  add->excludes(remove);
  edit->add_option("-o,--output", o.output, "Write the edited terrain here (default: replace the input)");
}

int runStacksEdit(const StacksEditOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  if (o.add.empty() == !o.remove) {
    return fail(makeError("give either --add MATERIAL or --remove"));
  }
  const std::string output = o.output.empty() ? o.input : o.output;
  if (!isStackFile(output)) return fail(makeError("the output '{}' must end in .tstack", output));
  static constexpr std::array<const char*, 4> kFields = {"x", "y", "z", "r"};
  Result<std::vector<double>> sphere = parseNumberFields(o.sphere, kFields, "sphere");
  if (!sphere) return fail(sphere.error());
  SphereEdit edit{(*sphere)[0], (*sphere)[1], (*sphere)[2], (*sphere)[3], kAir};
  if (!o.remove) {
    Result<StackMaterial> material = parseStackMaterial(o.add);
    if (!material) return fail(material.error());
    edit.material = material.value();
  }
  GeoReference georef;
  Result<std::vector<StackTerrain>> pyramid = readStackFile(o.input, &georef);
  if (!pyramid) return fail(pyramid.error());
  Result<StackRegion> region = applySphereEdit(pyramid->front(), edit);
  if (!region) return fail(makeError("{}: {}", o.input, region.error().message));
  if (region->empty()) {
    // Nothing to write: an output the caller expects would silently not exist.
    return fail(makeError("the sphere changes no stack of {} ({} where it reaches): nothing written",
                          o.input, o.remove ? "no material to remove" : "already that material"));
  }
  updatePyramid(pyramid.value(), region.value());
  if (Status written = writeStackFile(output, pyramid.value(), georef); !written) return fail(written.error());
  spdlog::info("{} {} stacks ({} x {} from column {}, row {}) and their {} levels above; wrote {} "
               "in {:.2f} s",
               o.remove ? "carved" : "filled", (region->x1 - region->x0 + 1) * (region->y1 - region->y0 + 1),
               region->x1 - region->x0 + 1, region->y1 - region->y0 + 1, region->x0, region->y0,
               pyramid->size() - 1, output,
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return 0;
}

}  // namespace tellus::cli
