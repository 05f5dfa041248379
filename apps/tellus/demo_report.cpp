#include "demo_report.hpp"

#include <fstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "tellus/core/atomic_output.hpp"

namespace tellus::cli {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// 1234567 -> "1,234,567".
std::string withThousands(std::uint64_t value) {
  const std::string digits = std::to_string(value);
  std::string grouped;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) grouped += ',';
    grouped += digits[i];
  }
  return grouped;
}

// The benchmark table as cells, header first, shared by the HTML and Markdown pages.
std::vector<std::vector<std::string>> benchTableCells(const json& report) {
  std::vector<std::vector<std::string>> rows = {
      {"renderer", "frame ms", "CPU ms", "GPU ms", "triangles", "SSE p95 px", "SSE p99 px",
       "crack pixels", "popping p99 px"}};
  for (const json& algo : report.at("algorithms")) {
    const json& s = algo.at("summary");
    const auto number = [&](const char* key, const char* format) {
      return s.contains(key) ? fmt::format(fmt::runtime(format), s.at(key).get<double>())
                             : std::string("-");
    };
    rows.push_back({algo.at("algo").get<std::string>(), number("frame_ms_median", "{:.1f}"),
                    number("cpu_ms_median", "{:.3f}"), number("gpu_ms_median", "{:.1f}"),
                    withThousands(std::uint64_t(s.value("triangles_median", 0.0))),
                    number("sse_px_p95", "{:.2f}"),
                    number("sse_px_p99", "{:.2f}"), number("crack_pixels_total", "{:.0f}"),
                    number("pop_px_p99", "{:.2f}")});
  }
  return rows;
}

std::string benchTableHtml(const json& report) {
  std::string html = "<table>\n";
  bool header = true;
  for (const auto& row : benchTableCells(report)) {
    html += "<tr>";
    for (const std::string& cell : row) {
      html += header ? fmt::format("<th>{}</th>", cell) : fmt::format("<td>{}</td>", cell);
    }
    html += "</tr>\n";
    header = false;
  }
  return html + "</table>\n";
}

std::string imageDetails(const DemoImage& image, std::string_view open, std::string_view close) {
  std::string details = fmt::format("{}{}{}: {} triangles, {:.0f} ms", open, image.algo, close,
                                    withThousands(image.stats.triangles), image.milliseconds);
  if (!image.errorShading.empty()) details += fmt::format("; its error shading: {}", image.errorShading);
  return details;
}

std::string cameraString(const Camera& c) {
  return fmt::format("{:.1f},{:.1f},{:.1f},{:.2f},{:.2f},{:.1f}", c.position.x, c.position.y,
                     c.position.z, c.yawDeg, c.pitchDeg, c.fovYDeg);
}

constexpr const char* kErrorShadingNote =
    "Each renderer lit, and beside it shaded by the screen-space error it knows of (green 0 px, "
    "red 4 px and more); under each, what that error is. The benchmark below measures the real "
    "error of every pixel against the full-resolution surface.";

// The page's opening: what Tellus is and what the page shows, for someone who has never heard
// of it.
constexpr const char* kIntroduction =
    "Tellus is an engine and toolset for drawing very large terrains in real time: real elevation "
    "data (SRTM, GeoTIFF, ETOPO) goes in, a compressed tile pyramid on disk comes out, and a dozen "
    "level-of-detail renderers from the research literature draw it, flat or on the globe, each "
    "measured the same way (frame time, triangles, screen-space error against the full-resolution "
    "surface, cracks, popping). This page was made by one command, <code>tellus demo</code>: "
    "flythroughs first, then every renderer on the same view of a generated mountain range, their "
    "benchmark along a flyover, a gallery, stack terrain with caves and arches, and the terrain "
    "on a generated planet seen from orbit down to the ground. Every picture says the command "
    "that makes it again.";
constexpr const char* kIntroductionMarkdown =
    "Tellus is an engine and toolset for drawing very large terrains in real time: real elevation "
    "data (SRTM, GeoTIFF, ETOPO) goes in, a compressed tile pyramid on disk comes out, and a dozen "
    "level-of-detail renderers from the research literature draw it, flat or on the globe, each "
    "measured the same way (frame time, triangles, screen-space error against the full-resolution "
    "surface, cracks, popping). This page was made by one command, `tellus demo`: flythroughs "
    "first, then every renderer on the same view of a generated mountain range, their benchmark "
    "along a flyover, a gallery, stack terrain with caves and arches, and the terrain on a "
    "generated planet seen from orbit down to the ground. Every picture says the command that "
    "makes it again.";

// Under the globe benchmark's table.
constexpr const char* kGlobeBenchNote =
    "All are measured against the store at its deepest depth wherever a pixel lands. The globe "
    "reference draws the region each part of the path sees at the deepest depth that fits its "
    "sample budget, which near the ground is coarser than the store: its error there is that "
    "budget's. RINGO streams the store's own depth around the camera (settled here: a descent in "
    "a few frames is a time-lapse). The spiral draws one static spiral of about the same number of "
    "triangles at every height, its radii from occlusion-query feedback a frame late.";

// The charts `bench --plots` writes, with captions.
constexpr std::pair<const char*, const char*> kCharts[] = {
    {"comparison.png",
     "Every renderer on one chart: triangles against screen-space error p99 (marker area: frame "
     "time), and the table sorted by frame time"},
    {"frame_time.png", "Frame time"},
    {"triangles.png", "Triangles per frame"},
    {"cpu.png", "CPU per frame: the render thread's LOD work and the background threads' loads"},
    {"error_histogram.png", "Screen-space error over all pixels of all frames"},
    {"popping.png", "Popping: how far the surface jumps when the level of detail changes"},
    {"contact_sheet.png", "Sampled frames"},
};

// Reads dir/folder/bench.json.
Result<json> readBenchReport(const fs::path& dir, const std::string& folder) {
  const fs::path reportFile = dir / folder / "bench.json";
  std::ifstream in(reportFile);
  if (!in) return makeError("cannot read the benchmark report '{}'", reportFile.string());
  json report = json::parse(in, nullptr, false);
  if (report.is_discarded() || !report.contains("algorithms")) {
    return makeError("'{}' is not a benchmark report", reportFile.string());
  }
  return report;
}

std::string pathLineOf(const json& report, const std::string& glRenderer) {
  return fmt::format(
      "Path {}, {} frames after {} warm-up, {} x {} pixels, on {}. Frame ms = max(CPU, GPU), "
      "medians; SSE and popping percentiles over all pixels of all frames.",
      report.value("path", std::string()), report.value("frames", 0),
      report.value("warmup_frames", 0), report["size"][0].get<int>(),
      report["size"][1].get<int>(), glRenderer);
}

// The charts of dir/folder that exist, with captions (`along`: "along the flyover").
void appendCharts(const fs::path& dir, const std::string& folder, std::string_view along,
                  std::string& html, std::string& markdown) {
  for (const auto& [file, caption] : kCharts) {
    if (!fs::exists(dir / folder / file)) continue;
    const std::string path = folder + "/" + file;
    const std::string title =
        std::string_view(file) == "frame_time.png" ? fmt::format("Frame time {}", along) : caption;
    html += fmt::format("<h3>{}</h3>\n<img src=\"{}\" alt=\"{}\">\n", title, path, title);
    markdown += fmt::format("### {}\n\n![{}]({})\n\n", title, title, path);
  }
}

std::string geoCameraString(const GeoCamera& c) {
  return fmt::format("{:.4f},{:.4f},{:.0f},{:.1f},{:.1f},{:.0f}", c.latDeg, c.lonDeg,
                     c.altitudeM, c.headingDeg, c.pitchDeg, c.fovYDeg);
}

// The globe section: the planet, its stills, the benchmark along a descent.
Status appendGlobeSection(const fs::path& dir, const DemoGlobe& globe,
                          const std::string& glRenderer, std::string& html,
                          std::string& markdown) {
  Result<json> report = readBenchReport(dir, globe.benchFolder);
  if (!report) return report.error();
  html += fmt::format("<h2>The globe</h2>\n<p>{}</p>\n", globe.summary);
  markdown += fmt::format("## The globe\n\n{}\n\n", globe.summary);
  for (const DemoGlobeImage& image : globe.images) {
    const std::string details = fmt::format(
        "{}: {} triangles, {:.0f} ms; geo camera (lat, lon, alt, heading, pitch, fov)", image.algo,
        withThousands(image.stats.triangles), image.milliseconds);
    html += fmt::format("<h3>{}</h3>\n<img src=\"{}\" alt=\"{}\">\n<p>{} <code>{}</code></p>\n",
                        image.title, image.file, image.title, details,
                        geoCameraString(image.camera));
    markdown += fmt::format("### {}\n\n![{}]({})\n\n{} `{}`\n\n", image.title, image.title,
                            image.file, details, geoCameraString(image.camera));
  }
  const std::string pathLine = pathLineOf(report.value(), glRenderer);
  html += fmt::format(
      "<h3>Down to the ground</h3>\n<p>{}</p>\n{}<p>{}</p><p>Reproduce: <code>{}</code></p>\n",
      pathLine, benchTableHtml(report.value()), kGlobeBenchNote, globe.benchCommand);
  markdown += fmt::format("### Down to the ground\n\n{}\n\n{}\n{}\n\nReproduce: `{}`\n\n",
                          pathLine, benchTableMarkdown(report.value()), kGlobeBenchNote,
                          globe.benchCommand);
  appendCharts(dir, globe.benchFolder, "along the descent", html, markdown);
  return {};
}

}  // namespace

std::string benchTableMarkdown(const json& report) {
  std::string markdown;
  bool header = true;
  for (const auto& row : benchTableCells(report)) {
    markdown += "|";
    for (const std::string& cell : row) markdown += " " + cell + " |";
    markdown += "\n";
    if (header) {
      markdown += "|";
      for (std::size_t i = 0; i < row.size(); ++i) markdown += i == 0 ? " --- |" : " ---: |";
      markdown += "\n";
    }
    header = false;
  }
  return markdown;
}

namespace {

// One titled image with its renderer, timing and camera, to both pages.
void appendImage(const DemoImage& image, std::string& html, std::string& markdown) {
  html += fmt::format("<h3>{}</h3>\n<img src=\"{}\" alt=\"{}\">\n<p>{}; camera <code>{}</code></p>\n",
                      image.title, image.file, image.title,
                      imageDetails(image, "<code>", "</code>"), cameraString(image.camera));
  markdown += fmt::format("### {}\n\n![{}]({})\n\n{}; camera `{}`\n\n", image.title,
                          image.title, image.file, imageDetails(image, "`", "`"),
                          cameraString(image.camera));
}

}  // namespace

Status writeDemoPages(const fs::path& dir, const DemoPage& page) {
  Result<json> read = readBenchReport(dir, page.benchFolder);
  if (!read) return read.error();
  const json& report = read.value();
  const std::string pathLine = pathLineOf(report, page.glRenderer);

  std::string html = fmt::format(
      "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>Tellus demo</title>\n"
      "<style>body{{font-family:sans-serif;max-width:1320px;margin:2em auto;background:#15181c;"
      "color:#dde}} img{{width:100%;border-radius:4px}} code{{color:#9cf}} "
      ".pair{{display:grid;grid-template-columns:1fr 1fr;gap:12px}} "
      "table{{border-collapse:collapse;margin:1em 0}} td,th{{padding:4px 10px;"
      "border-bottom:1px solid #445;text-align:right}} td:first-child,th:first-child"
      "{{text-align:left}} video{{width:100%;border-radius:4px}}</style></head><body>\n"
      "<h1>Tellus demo</h1>\n<p>{}</p>\n<p>{}</p>\n<p>{}</p>\n"
      "<p>Files: <a href=\"terrain.tif\">terrain.tif</a> (GeoTIFF, metres), "
      "<code>terrain.tstore</code> (the tile pyramid).</p>\n",
      kIntroduction, page.terrainSummary, page.storeSummary);
  std::string markdown = fmt::format(
      "# Tellus demo\n\n{}\n\n{}\n\n{}\n\nFiles: `terrain.tif` (GeoTIFF, metres), `terrain.tstore` "
      "(the tile pyramid).\n\n",
      kIntroductionMarkdown, page.terrainSummary, page.storeSummary);
  // The flythroughs first: the flat world's, then the globe's.
  std::vector<DemoVideo> videos = page.videos;
  if (page.globe) videos.insert(videos.end(), page.globe->videos.begin(), page.globe->videos.end());
  if (!videos.empty()) {
    html += "<h2>Flythroughs</h2>\n";
    markdown += "## Flythroughs\n\n";
  }
  for (const DemoVideo& video : videos) {
    html += fmt::format("<h3>{}</h3>\n<video src=\"{}\" controls loop muted playsinline></video>\n"
                        "<p>Make it again: <code>{}</code></p>\n",
                        video.title, video.file, video.command);
    markdown += fmt::format("### {}\n\n[{}]({}) (H.264 video)\n\nMake it again: `{}`\n\n", video.title,
                            video.file, video.file, video.command);
  }
  html += fmt::format("<h2>Every renderer, one view</h2>\n<p>{}</p>\n", kErrorShadingNote);
  markdown += fmt::format("## Every renderer, one view\n\n{}\n\n", kErrorShadingNote);
  for (std::size_t i = 0; i + 1 < page.comparison.size(); i += 2) {
    const DemoImage& lit = page.comparison[i];
    const DemoImage& error = page.comparison[i + 1];
    html += fmt::format(
        "<h3>{}</h3>\n<div class=\"pair\"><img src=\"{}\" alt=\"{}\"><img src=\"{}\" "
        "alt=\"{}\"></div>\n<p>{}</p>\n",
        lit.title, lit.file, lit.title, error.file, error.title,
        imageDetails(lit, "<code>", "</code>"));
    markdown += fmt::format("### {}\n\n![{}]({}) ![{}]({})\n\n{}\n\n", lit.title, lit.title,
                            lit.file, error.title, error.file, imageDetails(lit, "`", "`"));
  }
  if (!page.comparison.empty()) {
    const std::string camera = cameraString(page.comparison.front().camera);
    html += fmt::format("<p>Camera <code>{}</code> (x, y, z, yaw, pitch, fov).</p>\n", camera);
    markdown += fmt::format("Camera `{}` (x, y, z, yaw, pitch, fov).\n\n", camera);
  }

  html += fmt::format("<h2>Along a flyover</h2>\n<p>{}</p>\n{}<p>Reproduce: <code>{}</code></p>\n",
                      pathLine, benchTableHtml(report), page.benchCommand);
  markdown += fmt::format("## Along a flyover\n\n{}\n\n{}\nReproduce: `{}`\n\n", pathLine,
                          benchTableMarkdown(report), page.benchCommand);
  appendCharts(dir, page.benchFolder, "along the flyover", html, markdown);

  html += "<h2>Gallery</h2>\n";
  markdown += "## Gallery\n\n";
  for (const DemoImage& image : page.gallery) appendImage(image, html, markdown);
  if (page.stacks) {
    html += fmt::format("<h2>Stack terrain (seed 003)</h2>\n<p>{}</p>\n", page.stacks->summary);
    markdown += fmt::format("## Stack terrain (seed 003)\n\n{}\n\n", page.stacks->summary);
    for (const DemoImage& image : page.stacks->images) appendImage(image, html, markdown);
  }
  if (page.globe) {
    if (Status s = appendGlobeSection(dir, *page.globe, page.glRenderer, html, markdown); !s) {
      return s;
    }
  }
  html += "</body></html>\n";
  for (const auto& [name, text] :
       {std::pair{"index.html", html}, std::pair{"index.md", markdown}}) {
    if (Status written = writeTextFileAtomically(dir / name, text); !written) return written;
  }
  return {};
}

}  // namespace tellus::cli
