#include "tellus/render/terrain_renderer.hpp"

#include "tellus/render/imagery/imagery_textures.hpp"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "tellus/gl/program.hpp"

namespace tellus {

std::string countText(std::uint64_t n) {
  if (n >= 10'000'000) return fmt::format("{:.1f} M", double(n) / 1e6);
  if (n >= 10'000) return fmt::format("{:.1f} k", double(n) / 1e3);
  return fmt::format("{}", n);
}

Result<ShadingMode> parseShadingMode(std::string_view name) {
  for (ShadingMode mode :
       {ShadingMode::Lit, ShadingMode::LevelOfDetail, ShadingMode::ScreenSpaceError}) {
    if (name == shadingModeName(mode)) return mode;
  }
  return makeError("unknown shading mode '{}' (expected lit, lod or sse)", name);
}

std::string_view shadingModeName(ShadingMode mode) {
  switch (mode) {
    case ShadingMode::LevelOfDetail:
      return "lod";
    case ShadingMode::ScreenSpaceError:
      return "sse";
    case ShadingMode::Lit:
      break;
  }
  return "lit";
}

void applyShadingMode(const gl::Program& program, const ViewSetup& view,
                      const RenderSettings& settings) {
  applyShading(program, settings.shading);
  program.set("uShadingMode", int(settings.mode));
  const double halfFov = 0.5 * view.camera.fovYDeg * std::numbers::pi / 180.0;
  program.set("uPixelsPerRadian", float(0.5 * view.height / std::tan(halfFov)));
  program.set("uSseRedPx", settings.sseRedPx);
  if (settings.imagery) {
    settings.imagery->apply(program, view);
  } else {
    program.set("uImageryLayerCount", 0);
  }
}

}  // namespace tellus
