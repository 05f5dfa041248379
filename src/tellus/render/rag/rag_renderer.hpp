#pragma once
// RAG, recursive adaptive GPU refinement (seed 004): a coarse mesh refined on the GPU every
// frame by a geometry shader whose output transform feedback captures into one of two buffers
// that take turns as input and output ("recursion"), with the rasteriser off until the refined
// mesh is drawn. No CPU work per triangle: the CPU sets uniforms and issues one draw per pass.
// The CPU reference it is tested against is rag::refine() (src/tellus/lod/rag/).
//
// Counts come from queries: per pass, the primitives the geometry shader generated and those
// transform feedback wrote. A pass that generated more than the buffers hold has overflowed;
// the buffers then grow. With exactCounts (stills, tests) the queries are read at the end of
// the frame, and an overflowed frame is refined again in the grown buffers, so no frame is
// ever drawn truncated; otherwise they are read a frame later without stalling (the frame's
// triangle count is then the previous frame's), and a truncated frame is counted
// (overflowedFrames()) and logged.
//
// Heights come from one R32F texture of the height grid. A grid with more samples a side than
// the texture may hold (the GPU's limit, or RagOptions::maxMapSamples) is refined against the
// finest pyramid level that fits (rag::heightMapAtLevel): the level's geometric error is then
// the floor of RAG's vertical error, and the error shading adds it. Needs a current GL 4.5
// context for its whole life.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tellus/core/result.hpp"
#include "tellus/dem/height_grid.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/framebuffer.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/query.hpp"
#include "tellus/gl/texture.hpp"
#include "tellus/gl/transform_feedback.hpp"
#include "tellus/gl/vertex_array.hpp"
#include "tellus/lod/rag/rag_height_map.hpp"
#include "tellus/lod/rag/rag_mesh.hpp"
#include "tellus/lod/rag/rag_refinement.hpp"
#include "tellus/render/terrain_renderer.hpp"

namespace tellus {

inline constexpr int kRagMaxPasses = 8;

struct RagOptions {
  std::string name = "rag";
  // Variant, thresholds, early clipping; long edges split (beyond the seed).
  rag::RefinementSettings refinement{.edgeLengthPx = rag::kDefaultEdgeLengthPx};
  int coarseVertices = rag::kDefaultCoarseVertices;
  // Align the coarse mesh to the samples (rag::buildAlignedCoarseMesh) and read heights from the
  // reference's triangles (rag::MapSampling::Surface): needed for views from near the ground,
  // where the seed's mesh (false: unaligned, nearest samples) is off by hundreds of pixels.
  bool alignCoarseMesh = true;
  // Passes per frame; with adaptivePasses the most (a pass is skipped once the previous
  // frame's pass added fewer than adaptiveMinGrowth times the triangles it read). 7: the
  // default mesh's cells of 64 samples reach single samples in 6, and the 7th splits the
  // cells' other diagonals where they show (the seed's default was 6).
  int passes = 7;
  bool adaptivePasses = false;
  float adaptiveMinGrowth = 0.05f;
  bool exactCounts = false;
  // Height-map samples a side at most (0: the GPU's texture limit); a larger grid is refined
  // against a coarser pyramid level of itself.
  int maxMapSamples = 0;
};

// What the last frame's passes did, from the queries.
struct RagPassCounts {
  int passes = 0;
  std::array<std::uint64_t, kRagMaxPasses> generated{};  // triangles the pass emitted
  std::array<std::uint64_t, kRagMaxPasses> written{};    // of those, captured
};

class RagRenderer final : public TerrainRenderer {
 public:
  // Errors: options out of range, a grid beyond the texture size, shaders that do not build.
  static Result<std::unique_ptr<RagRenderer>> create(const HeightGrid& grid,
                                                     const RagOptions& options);

  std::string_view name() const override { return options_.name; }
  FrameStats draw(const ViewSetup& view, const RenderSettings& settings) override;
  // This frame's triangle count from its queries (waits for them; grows overflowed buffers).
  void finishStats(FrameStats& stats) override;
  // Refines again with the previous frame's view and pass count and draws that mesh from `view`.
  bool drawPreviousSelection(const ViewSetup& view, const RenderSettings& settings) override;
  std::vector<std::string> frameReport() const override;

  // Refines for `view` as draw() would and reads the refined mesh back (tests).
  std::vector<rag::Triangle> refineAndRead(const ViewSetup& view, float verticalExaggeration);

  const RagOptions& options() const { return options_; }
  const std::vector<rag::Triangle>& coarseMesh() const { return coarse_; }
  // The refinement settings the passes run with: the options', with the map sampling that
  // follows from alignCoarseMesh (what the CPU reference must be given to match them).
  const rag::RefinementSettings& refinement() const { return options_.refinement; }
  // The latest counts read (this frame's with exactCounts, else an earlier frame's).
  const RagPassCounts& lastCounts() const { return lastCounts_; }
  std::uint64_t capacityTriangles() const { return capacity_; }
  std::uint64_t overflowedFrames() const { return overflowedFrames_; }
  // The pyramid level of the grid the height map holds (0: the grid itself) and its geometric
  // error in metres.
  int mapLevel() const { return mapLevel_; }
  float mapErrorM() const { return mapErrorM_; }
  int passesThisFrame() const { return passesThisFrame_; }

 private:
  struct QuerySet {
    std::array<gl::Query, kRagMaxPasses> generated, written;
    int passes = 0;
    bool pending = false;
  };

  struct Selection {  // what a frame refined for: its view and pass count
    rag::RefinementView view;
    int passes = 0;
  };

  RagRenderer() = default;
  void allocateBuffers(std::uint64_t triangles);
  void setRefinementUniforms(const gl::Program& program, const rag::RefinementView& view) const;
  // Runs `passes` passes; returns the index of the buffer holding the result.
  int runPasses(int passes, QuerySet& queries);
  // Reads a finished query set into `counts` and grows the buffers if a pass overflowed;
  // returns true then.
  bool readCounts(QuerySet& queries, RagPassCounts& counts);
  // readCounts, then the frame's counts and the adaptive pass count. Returns true when a pass
  // overflowed.
  bool absorbCounts(QuerySet& queries);
  // Draws the refined mesh in `resultBuffer` (the coarse mesh when passes is 0) from `view`.
  void drawRefined(const rag::RefinementView& refinementView, const ViewSetup& view,
                   const RenderSettings& settings, int resultBuffer, int passes);
  // Counts and logs a frame drawn from buffers that overflowed (they have grown since).
  void noteTruncatedFrame();
  void drawMesh(const gl::Program& program, int resultBuffer, int passes) const;

  RagOptions options_;
  std::vector<rag::Triangle> coarse_;
  double spacingXM_ = 1.0, spacingYM_ = 1.0;
  HeightRange heightRange_;
  int mapLevel_ = 0;
  float mapErrorM_ = 0.0f;
  gl::Texture heights_;
  gl::Program refine_, fill_, wire_;
  gl::Buffer coarseBuffer_;
  gl::VertexArray coarseArray_;
  std::array<gl::Buffer, 2> buffers_;
  std::array<gl::VertexArray, 2> arrays_;
  std::array<gl::TransformFeedback, 2> feedback_;
  std::uint64_t capacity_ = 0;  // triangles each buffer holds
  std::array<QuerySet, 2> querySets_;
  QuerySet replayQueries_;  // drawPreviousSelection's
  std::optional<Selection> currentSelection_, previousSelection_;
  int frame_ = 0;
  int adaptivePasses_ = 1;
  int passesThisFrame_ = 0;
  RagPassCounts lastCounts_;
  std::uint64_t overflowedFrames_ = 0;
  gl::Framebuffer emptyTarget_;  // refineAndRead's target
};

}  // namespace tellus
