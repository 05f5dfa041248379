// tellus_embed: the smallest useful program on Tellus's public API (include/tellus/tellus.hpp,
// the only headers the package installs). It opens a tile store (a file or an http:// URL),
// makes a headless OpenGL 4.5 context, and renders frames of an orbit around the terrain with a
// renderer picked by name (default rings, seed 000; any name tellus::listRenderers() gives),
// printing each frame's triangles and what the renderer says of its frame, and writes the last
// frame as a PNG. With `--list` it prints the renderers and their options instead.
//
//   tellus_embed STORE OUT.png [FRAMES] [RENDERER]
//   tellus_embed --list
#include <cstdio>
#include <cstdlib>
#include <string>

#include "tellus/tellus.hpp"

namespace {

int failWith(const std::string& what, const tellus::Error& error) {
  std::fprintf(stderr, "tellus_embed: %s: %s\n", what.c_str(), error.message.c_str());
  return 1;
}

void listRenderers() {
  for (const tellus::RendererInfo& renderer : tellus::listRenderers()) {
    std::printf("%-16s %s%s\n", renderer.name.c_str(), renderer.description.c_str(),
                renderer.variant ? " (variant)" : "");
    for (const tellus::RendererOptionInfo& option : renderer.options) {
      std::printf("    %-28s %-8s %s\n", option.name.c_str(), option.defaultValue.c_str(),
                  option.help.c_str());
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 2 && std::string(argv[1]) == "--list") {
    listRenderers();
    return 0;
  }
  if (argc < 3 || argc > 5) {
    std::fprintf(stderr, "usage: tellus_embed STORE OUT.png [FRAMES] [RENDERER]\n"
                         "       tellus_embed --list\n");
    return 2;
  }
  const std::string storePath = argv[1], outputPath = argv[2];
  const int frames = argc >= 4 ? std::atoi(argv[3]) : 8;
  const std::string renderer = argc == 5 ? argv[4] : "rings";
  if (frames < 1 || frames > 10000) {
    std::fprintf(stderr, "tellus_embed: FRAMES must be 1 to 10000, not '%s'\n", argv[3]);
    return 2;
  }

  auto terrain = tellus::Terrain::open(storePath);
  if (!terrain) return failWith("cannot open the store", terrain.error());
  const tellus::TerrainFacts& facts = terrain.value().facts();
  std::printf("%s: %d x %d samples, %.0f x %.0f m, heights %.0f to %.0f m, %d levels\n",
              facts.source.c_str(), facts.samplesX, facts.samplesY, facts.widthM, facts.depthM,
              facts.minHeightM, facts.maxHeightM, facts.levels);

  // A headless GL 4.5 context (EGL), current on this thread from now on.
  auto gl = tellus::GraphicsContext::createHeadless();
  if (!gl) return failWith("no OpenGL 4.5 context", gl.error());

  // The renderer by name, with one of its options set as the command line would
  // (--rings-gpu-slots 64); stills wait for the tiles each frame needs.
  tellus::ViewSettings settings;
  settings.width = 640;
  settings.height = 360;
  if (renderer == "rings") settings.options["rings-gpu-slots"] = "64";
  auto view = tellus::TerrainView::create(terrain.value(), renderer, settings);
  if (!view) return failWith("cannot create renderer " + renderer, view.error());

  tellus::Picture last;
  for (int frame = 0; frame < frames; ++frame) {
    // An orbit: the overview turned a full circle over the frames.
    const double yaw = 360.0 * frame / frames;
    const tellus::Viewpoint viewpoint = tellus::overviewOf(terrain.value(), 16.0 / 9.0, yaw);
    tellus::FrameReport report;
    auto picture = view.value().draw(viewpoint, &report);
    if (!picture) return failWith("cannot render a frame", picture.error());
    std::printf("frame %d: yaw %.0f deg, %llu triangles, %llu tiles wanted\n", frame, yaw,
                static_cast<unsigned long long>(report.triangles),
                static_cast<unsigned long long>(report.tilesWanted));
    for (const std::string& line : report.lines) std::printf("  %s\n", line.c_str());
    last = std::move(picture.value());
  }
  if (auto written = last.savePng(outputPath); !written) {
    return failWith("cannot write " + outputPath, written.error());
  }
  std::printf("wrote %s (%dx%d)\n", outputPath.c_str(), last.width, last.height);
  return 0;
}
