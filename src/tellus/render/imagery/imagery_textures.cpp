#include "tellus/render/imagery/imagery_textures.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include <spdlog/spdlog.h>

#include "tellus/core/geodesy.hpp"
#include "tellus/gl/gpu_wait.hpp"

namespace tellus {
namespace {

constexpr GLuint kPagesUnit = 14;     // imagery.glsl: uImageryPages
constexpr GLuint kPageTableBinding = 14;
constexpr GLuint kFeedbackBinding = 15;

double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// The pixels-per-texel value a density bin stands for (its geometric centre).
double densityOfBin(int bin) {
  return std::exp2((double(bin - ImageryTextures::kDensityBins / 2) + 0.5) / 4.0);
}

double histogramPercentile(const std::vector<std::uint32_t>& bins, double p) {
  std::uint64_t total = 0;
  for (std::uint32_t c : bins) total += c;
  if (total == 0) return 0.0;
  const double target = p * double(total);
  std::uint64_t seen = 0;
  for (std::size_t b = 0; b < bins.size(); ++b) {
    seen += bins[b];
    if (double(seen) >= target) return densityOfBin(int(b));
  }
  return densityOfBin(int(bins.size()) - 1);
}

}  // namespace

Result<std::unique_ptr<ImageryTextures>> ImageryTextures::create(std::vector<ImageryLayer> layers,
                                                                 const ImageryBudget& budget, ImageryFrame frame) {
  if (layers.empty()) return makeError("imagery: no layers");
  if (int(layers.size()) > kMaxLayers) {
    return makeError("imagery: {} sources; at most {} can be draped at once", layers.size(), kMaxLayers);
  }
  const int tileSize = layers.front().pyramid.tileSize();
  ImageryPageLayout layout;
  for (const ImageryLayer& layer : layers) {
    const ImageryPyramid& p = layer.pyramid;
    if (p.tileSize() != tileSize) {
      return makeError("imagery '{}' has {}-texel tiles, '{}' {}: one size for all", p.path().string(),
                       p.tileSize(), layers.front().pyramid.path().string(), tileSize);
    }
    std::vector<ImageryLevelPages> levels;
    for (int m = 0; m < p.levels(); ++m) levels.push_back({0, p.tilesX(m), p.tilesY(m)});
    if (Status added = layout.addLayer(levels); !added) {
      return makeError("imagery '{}': {}", p.path().string(), added.error().message);
    }
  }
  const int slotSide = tileSize + 2 * kBorder;
  const std::uint64_t slotBytes = std::uint64_t(slotSide) * slotSide * 4;
  GLint maxLayers = 0;
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
  const int slots = int(std::min<std::uint64_t>(budget.memoryBytes / slotBytes, std::uint64_t(maxLayers)));
  Result<ImageryResidency> residency = ImageryResidency::create(layout, slots, budget.uploadsPerFrame);
  if (!residency) {
    return makeError("imagery budget of {} MiB ({} pages of {} KiB): {}", budget.memoryBytes >> 20, slots,
                     slotBytes >> 10, residency.error().message);
  }
  std::unique_ptr<ImageryTextures> t(new ImageryTextures(std::move(residency.value())));
  t->layers_ = std::move(layers);
  t->tileSize_ = tileSize;
  t->placementFrame_ = frame;
  t->pageCount_ = layout.pageCount();
  t->pages_ = gl::Texture::create2DArray(GL_RGBA8, slotSide, slotSide, slots);
  t->pages_.setFilter(GL_LINEAR, GL_LINEAR);
  t->pages_.setWrap(GL_CLAMP_TO_EDGE);
  t->pageTable_.assign(std::size_t(t->pageCount_), 0u);
  t->pageTableBuffer_ = gl::Buffer(t->pageTable_.size() * 4, t->pageTable_.data(), GL_DYNAMIC_STORAGE_BIT);
  const std::size_t feedbackBytes = (std::size_t(t->pageCount_) + kDensityBins) * 4;
  const std::vector<std::uint32_t> zeros(std::size_t(t->pageCount_) + kDensityBins, 0u);
  t->feedback_ = gl::Buffer(feedbackBytes, zeros.data(), 0);
  for (Readback& r : t->readbacks_) r.buffer = gl::Buffer(feedbackBytes, nullptr, 0);
  t->staging_.resize(std::size_t(slotBytes));
  t->info_.layers = int(t->layers_.size());
  t->info_.slots = slots;
  t->info_.budgetBytes = std::uint64_t(slots) * slotBytes;
  return t;
}

void ImageryTextures::read(Readback& readback) {
  std::vector<std::uint32_t> values(std::size_t(pageCount_) + kDensityBins);
  gl::readCompletedBuffer(readback.buffer.id(), 0, values.size() * 4, values.data());
  readback.queued = false;
  std::vector<int> wanted;
  for (int page = 0; page < pageCount_; ++page) {
    if (values[std::size_t(page)] == std::uint32_t(readback.frame)) wanted.push_back(page);
  }
  residency_.want(wanted, readback.frame);
  const std::vector<std::uint32_t> bins(values.begin() + pageCount_, values.end());
  info_.texelPxP50 = histogramPercentile(bins, 0.50);
  info_.texelPxP95 = histogramPercentile(bins, 0.95);
  info_.feedbackFrame = readback.frame;
}

void ImageryTextures::beginFrame(bool wait) {
  const auto start = std::chrono::steady_clock::now();
  // Oldest first: each report replaces the wanted set of the one before.
  std::array<Readback*, 3> order{};
  for (std::size_t k = 0; k < readbacks_.size(); ++k) order[k] = &readbacks_[k];
  std::sort(order.begin(), order.end(), [](const Readback* a, const Readback* b) { return a->frame < b->frame; });
  for (Readback* r : order) {
    if (!r->queued) continue;
    if (wait) r->fence.wait();
    if (!r->fence.passed()) break;  // later ones are later still
    read(*r);
  }
  const ImageryPlan plan = residency_.plan();
  for (const ImageryUpload& upload : plan.uploads) transfer(upload);
  if (!plan.uploads.empty()) {
    pageTable_ = residency_.pageTable();
    pageTableBuffer_.upload(0, pageTable_.size() * 4, pageTable_.data());
  }
  const std::uint64_t slotBytes = staging_.size();
  info_.uploads = int(plan.uploads.size());
  info_.uploadBytes = std::uint64_t(plan.uploads.size()) * slotBytes;
  info_.evictions = plan.evictions;
  info_.pending = plan.pending;
  info_.unplaceable = plan.unplaceable;
  info_.residentPages = residency_.residentCount();
  info_.residentBytes = std::uint64_t(info_.residentPages) * slotBytes;
  info_.updateMs = millisecondsSince(start);
}

void ImageryTextures::transfer(const ImageryUpload& upload) {
  const ImageryPageKey key = residency_.layout().keyOf(upload.page);
  const ImageryLayer& layer = layers_[std::size_t(key.layer)];
  const ImageryPyramid& pyramid = layer.pyramid;
  const int t = tileSize_, side = t + 2 * kBorder;
  // A layer round the globe lends its border across the antimeridian (where its tiles fill the
  // level exactly).
  const bool wraps = layer.wrapTexels > 0.0 && pyramid.levelWidth(key.level) % t == 0;
  std::fill(staging_.begin(), staging_.end(), std::uint8_t(0));
  // The page and the border its eight neighbours lend (transparent beyond the level's tiles).
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const int tilesX = pyramid.tilesX(key.level);
      const int nx = wraps ? (key.x + dx + tilesX) % tilesX : key.x + dx, ny = key.y + dy;
      if (nx < 0 || ny < 0 || nx >= pyramid.tilesX(key.level) || ny >= pyramid.tilesY(key.level)) continue;
      const std::span<const std::byte> tile = pyramid.tile(key.level, nx, ny);
      // Rows and columns of this neighbour that fall in the slot: slot coordinate = border +
      // dx * t + neighbour coordinate.
      const int c0 = std::max(0, -kBorder - dx * t), c1 = std::min(t, side - kBorder - dx * t);
      const int r0 = std::max(0, -kBorder - dy * t), r1 = std::min(t, side - kBorder - dy * t);
      if (c0 >= c1 || r0 >= r1) continue;
      for (int row = r0; row < r1; ++row) {
        const int slotRow = kBorder + dy * t + row, slotCol = kBorder + dx * t + c0;
        std::memcpy(&staging_[(std::size_t(slotRow) * side + slotCol) * 4],
                    tile.data() + (std::size_t(row) * t + c0) * 4, std::size_t(c1 - c0) * 4);
      }
    }
  }
  pages_.uploadLayer(0, upload.slot, side, side, GL_RGBA, GL_UNSIGNED_BYTE, staging_.data());
}

void ImageryTextures::apply(const gl::Program& program, const ViewSetup& view) const {
  pages_.bindUnit(kPagesUnit);
  pageTableBuffer_.bindBase(GL_SHADER_STORAGE_BUFFER, kPageTableBinding);
  feedback_.bindBase(GL_SHADER_STORAGE_BUFFER, kFeedbackBinding);
  const int n = int(layers_.size());
  program.set("uImageryLayerCount", n);
  program.set("uImageryFrame", int(frame_));
  program.set("uImageryTileSize", tileSize_);
  program.set("uImageryBorder", kBorder);
  program.set("uImageryHistogramOffset", pageCount_);
  std::array<glm::vec2, kMaxLayers> cameraTexel{}, scale{};
  std::array<int, kMaxLayers> levels{};
  std::array<float, kMaxLayers> wrap{};
  constexpr int kMaxLevels = 16;
  std::array<glm::ivec4, kMaxLayers * kMaxLevels> levelPages{};
  // The camera in the placement's frame: world metres, or longitude and latitude (degrees).
  glm::dvec2 camera(view.camera.position);
  if (placementFrame_ == ImageryFrame::LonLat) {
    const wgs84::Geodetic g = wgs84::ecefToGeodetic(view.camera.position);
    camera = glm::dvec2(g.lonRad, g.latRad) / wgs84::kDegree;
  }
  program.set("uImageryCameraLonLat", glm::vec2(camera));
  for (int k = 0; k < n; ++k) {
    const ImageryPlacement& p = layers_[std::size_t(k)].placement;
    cameraTexel[std::size_t(k)] = glm::vec2(p.texelAt(camera));
    scale[std::size_t(k)] = glm::vec2(p.scale);
    levels[std::size_t(k)] = residency_.layout().levels(k);
    wrap[std::size_t(k)] = float(layers_[std::size_t(k)].wrapTexels);
    for (int m = 0; m < levels[std::size_t(k)]; ++m) {
      const ImageryLevelPages& l = residency_.layout().level(k, m);
      levelPages[std::size_t(k * kMaxLevels + m)] = glm::ivec4(l.firstPage, l.tilesX, l.tilesY, 0);
    }
  }
  program.setArray("uImageryCameraTexel", cameraTexel.data(), n);
  program.setArray("uImageryTexelsPerUnit", scale.data(), n);
  program.setArray("uImageryLevels", levels.data(), n);
  program.setArray("uImageryWrapTexels", wrap.data(), n);
  program.setArray("uImageryLevelPages", levelPages.data(), int(levelPages.size()));
}

void ImageryTextures::endFrame() {
  Readback& r = readbacks_[nextReadback_];
  if (!r.queued) {  // else its frame is still on the GPU: this frame's report is skipped
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glCopyNamedBufferSubData(feedback_.id(), r.buffer.id(), 0, 0, feedback_.size());
    const std::uint32_t zero = 0;
    glClearNamedBufferSubData(feedback_.id(), GL_R32UI, std::size_t(pageCount_) * 4, kDensityBins * 4,
                              GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    r.fence = gl::Fence::insert();
    r.frame = frame_;
    r.queued = true;
    nextReadback_ = (nextReadback_ + 1) % readbacks_.size();
  }
  ++frame_;
}

Result<std::vector<ImageryLayer>> imageryLayersOnGrid(const std::vector<std::filesystem::path>& sources,
                                                      const GeoReference& georef, int width, int height,
                                                      double spacingXM, double spacingYM,
                                                      const std::filesystem::path& cacheFolder) {
  std::vector<ImageryLayer> layers;
  for (const std::filesystem::path& source : sources) {
    Result<ImageryWarpGrid> grid = imageryGridOnStore(source, georef, width, height);
    if (!grid) return grid.error();
    ImageryBuildOptions options;
    options.warp = std::move(grid.value());
    Result<ImageryPyramid> pyramid = openCachedImageryPyramid(source, cacheFolder, options);
    if (!pyramid) return pyramid.error();
    ImageryLayer layer;
    layer.placement = placeOnFlatStore(pyramid->geoTransform(), georef.geoTransform, height, spacingXM, spacingYM);
    spdlog::info("imagery '{}': {} x {} texels over the terrain, {:.1f} x {:.1f} m a texel", source.string(),
                 pyramid->width(), pyramid->height(), 1.0 / layer.placement.scale.x,
                 -1.0 / layer.placement.scale.y);
    layer.pyramid = std::move(pyramid.value());
    layers.push_back(std::move(layer));
  }
  return layers;
}

Result<std::vector<ImageryLayer>> imageryLayersOnGlobe(const std::vector<std::filesystem::path>& sources,
                                                       const std::filesystem::path& cacheFolder) {
  std::vector<ImageryLayer> layers;
  for (const std::filesystem::path& source : sources) {
    Result<ImageryWarpGrid> grid = imageryGridOnGlobe(source);
    if (!grid) return grid.error();
    ImageryBuildOptions options;
    options.warp = std::move(grid.value());
    Result<ImageryPyramid> pyramid = openCachedImageryPyramid(source, cacheFolder, options);
    if (!pyramid) return pyramid.error();
    const std::array<double, 6>& g = pyramid->geoTransform();
    ImageryLayer layer;
    layer.placement.scale = glm::dvec2(1.0 / g[1], 1.0 / g[5]);
    layer.placement.offset = glm::dvec2(-g[0] / g[1], -g[3] / g[5]);
    if (pyramid->width() * g[1] >= 360.0 - 1e-9) layer.wrapTexels = 360.0 / g[1];
    spdlog::info("imagery '{}': {} x {} texels on the globe, {:.6f} degrees a texel", source.string(),
                 pyramid->width(), pyramid->height(), g[1]);
    layer.pyramid = std::move(pyramid.value());
    layers.push_back(std::move(layer));
  }
  return layers;
}

}  // namespace tellus
