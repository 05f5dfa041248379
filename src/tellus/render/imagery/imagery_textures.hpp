#pragma once
// One imagery service for every renderer: a virtual texture over imagery pyramids
// (dem/imagery_pyramid.hpp) paged in by what the frames' own lookups asked for
// (shaders/common/imagery.glsl writes a feedback buffer; it is read a frame or more late through
// fences, never waiting), within a memory budget (a fixed array of page slots) and an upload
// budget a frame, the coarser level shown until the finer one arrives
// (lod/imagery/imagery_pages.hpp). Renderers need not know about it: RenderSettings::imagery
// makes applyShadingMode() bind it to every terrain program, and the frame loop (bench, render,
// view) calls beginFrame() before a frame and endFrame() after it. Needs a current GL 4.5 context.
#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "tellus/core/camera.hpp"
#include "tellus/core/result.hpp"
#include "tellus/dem/imagery_pyramid.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/fence.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/texture.hpp"
#include "tellus/lod/imagery/imagery_pages.hpp"
#include "tellus/lod/imagery/imagery_placement.hpp"

namespace tellus {

struct ImageryBudget {
  std::uint64_t memoryBytes = std::uint64_t(96) << 20;  // page slots on the GPU, bytes
  int uploadsPerFrame = 8;                              // pages transferred a frame at most
};

// The frame the layers are placed in (ImageryPlacement's p): the flat world's metres, or the
// globe's longitude and latitude in degrees (camera positions are then ECEF).
enum class ImageryFrame { FlatWorld, LonLat };

struct ImageryLayer {
  ImageryPyramid pyramid;
  ImageryPlacement placement;
  // > 0: the layer repeats every this many level-0 texels east-west (a whole circle of
  // longitude: the lookups wrap across the antimeridian).
  double wrapTexels = 0.0;
};

// What the last beginFrame() did and what the last feedback read says.
struct ImageryPagingInfo {
  int layers = 0;
  int slots = 0, residentPages = 0;
  std::uint64_t residentBytes = 0;  // slots holding a page, bytes
  std::uint64_t budgetBytes = 0;    // all slots, bytes (the memory the service holds)
  int uploads = 0;                  // pages transferred this frame
  std::uint64_t uploadBytes = 0;
  int evictions = 0;
  int pending = 0;       // pages the latest feedback wanted that are still not resident
  int unplaceable = 0;   // of those, pages no slot could take (the memory budget is too small)
  double updateMs = 0.0; // render-thread time in beginFrame()
  std::uint64_t feedbackFrame = 0;  // the frame whose feedback was read last (0: none yet)
  // Screen pixels a texel of the level read covers, where imagery was drawn, over the last
  // feedback read (one pixel in 16): median and 95th percentile (0 when nothing was drawn).
  double texelPxP50 = 0.0, texelPxP95 = 0.0;
};

class ImageryTextures {
 public:
  static constexpr int kBorder = 1;      // texels each page slot repeats from its neighbours
  static constexpr int kMaxLayers = 4;   // shaders/common/imagery.glsl's kImageryMaxLayers
  static constexpr int kDensityBins = 128;  // imagery.glsl: quarter-octaves, 2^-16 to 2^16 px

  // Errors: no layers or too many, pyramids of different tile sizes, a budget below one page
  // a layer.
  static Result<std::unique_ptr<ImageryTextures>> create(std::vector<ImageryLayer> layers,
                                                         const ImageryBudget& budget,
                                                         ImageryFrame frame = ImageryFrame::FlatWorld);

  // Reads the feedback of earlier frames that the GPU has finished (every one, waiting, when
  // `wait`: stills and tests), lets the residency decide, transfers its pages and the page table.
  void beginFrame(bool wait = false);
  // Binds the pages, the page table and the feedback, and sets imagery.glsl's uniforms on
  // `program` for `view`. (applyShadingMode calls it.)
  void apply(const gl::Program& program, const ViewSetup& view) const;
  // Queues this frame's feedback for reading (a copy and a fence; nothing waits).
  void endFrame();

  const ImageryPagingInfo& frameInfo() const { return info_; }
  const ImageryResidency& residency() const { return residency_; }
  const std::vector<std::uint32_t>& pageTable() const { return pageTable_; }
  const std::vector<ImageryLayer>& layers() const { return layers_; }
  int tileSize() const { return tileSize_; }
  ImageryFrame placementFrame() const { return placementFrame_; }
  std::uint64_t frame() const { return frame_; }

 private:
  struct Readback {
    gl::Buffer buffer;
    gl::Fence fence;
    std::uint64_t frame = 0;
    bool queued = false;
  };
  explicit ImageryTextures(ImageryResidency residency) : residency_(std::move(residency)) {}
  void read(Readback& readback);
  void transfer(const ImageryUpload& upload);

  std::vector<ImageryLayer> layers_;
  ImageryResidency residency_;
  int tileSize_ = 0;
  int pageCount_ = 0;
  ImageryFrame placementFrame_ = ImageryFrame::FlatWorld;
  gl::Texture pages_;       // 2D array: a layer a slot, (tileSize + 2 border)^2 RGBA8
  gl::Buffer pageTableBuffer_;
  gl::Buffer feedback_;     // pageCount stamps, then the density histogram
  std::array<Readback, 3> readbacks_;
  std::size_t nextReadback_ = 0;
  std::vector<std::uint32_t> pageTable_;
  std::vector<std::uint8_t> staging_;
  std::uint64_t frame_ = 1;  // the stamp of the frame being drawn (0 never wanted anything)
  ImageryPagingInfo info_;
};

// The imagery pyramids of `sources` draped on a flat grid (a DEM or a store's level: its
// georeferencing `georef`, `width` x `height` samples `spacingXM` x `spacingYM` metres apart),
// each warped into the grid's CRS over the part it covers, built once and cached in
// `cacheFolder`, placed in the grid's flat world. Errors name the source: unreadable, not RGB,
// no overlap, a grid without a CRS.
Result<std::vector<ImageryLayer>> imageryLayersOnGrid(const std::vector<std::filesystem::path>& sources,
                                                      const GeoReference& georef, int width, int height,
                                                      double spacingXM, double spacingYM,
                                                      const std::filesystem::path& cacheFolder);

// The same for the globe: each source warped onto latitude/longitude (WGS 84) over its own
// footprint at its own resolution, placed by longitude and latitude (ImageryFrame::LonLat).
Result<std::vector<ImageryLayer>> imageryLayersOnGlobe(const std::vector<std::filesystem::path>& sources,
                                                       const std::filesystem::path& cacheFolder);

}  // namespace tellus
