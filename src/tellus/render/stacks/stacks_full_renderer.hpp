#pragma once
// `--algo stacks-full`: a stack terrain (seed 003) quadrangulated whole at its finest level by
// the GPU pipeline (StackQuadPipelineGpu), once, in fixed-size nodes, and drawn every frame
// with one indirect draw from the pipeline's counters: the ground truth the octree LOD renderer
// of part 2 is measured against. Lit, coloured by the vertices' material weights; the LOD
// shading shows it as level 0 and the error shading as exact (it is the finest level), and the
// wireframe overlay draws its triangles. Needs a current GL 4.5 context.
#include <memory>
#include <vector>

#include "tellus/gl/program.hpp"
#include "tellus/gl/vertex_array.hpp"
#include "tellus/render/stacks/stack_quad_pipeline.hpp"
#include "tellus/render/stacks/stack_sky_texture.hpp"
#include "tellus/render/terrain_renderer.hpp"
#include "tellus/render/drawing/wireframe_overlay.hpp"
#include "tellus/formats/stacks/material_stack.hpp"

namespace tellus {

struct StacksRenderOptions {
  QuadParams quad;     // node size, smoothing
  double cellM = 0.0;  // density cell height, metres (0: the stacks' spacing)
  // The octree renderer (`stacks`, stacks_lod_renderer.hpp):
  double tauPx = 10.0;       // split while a cell's screen-space extent exceeds this (seed: 10)
  // And while a node's geometric error (lost roofs, closed passages) exceeds this on screen;
  // 0: the seed's criterion alone.
  double errorTauPx = 20.0;
  int updatesPerFrame = 40;  // quadrangulations a frame at most (seed: ~40); 0: no limit
  // Past the lag bound (the drawn selection far too coarse for the view), the whole new
  // selection's meshes are asked for at once, this many a frame at most; 0: no limit.
  int burstPerFrame = 1024;
  int poolMiB = 512;         // the mesh cache's GPU pool (vertices and indices)
  // Geomorphing (beyond the seed): a split's new nodes slide from their parent's shape to
  // their own, and nodes about to merge slide to their parent's shape, over this many frames
  // each; 0: switch at once, as the seed does.
  int morphFrames = 4;
  // Seam blending (beyond the seed; lod/stacks/seam_blend.hpp): next to a coarser node, a node
  // takes the coarser surface over this many cells (at most (n - 1) / 2 - 1); 0: the seed's
  // stitching alone, which leaves a step of up to a coarser cell at the border.
  int seamBandCells = 4;
  // Tests of the quality harness only: leave out one quad in every `holeEvery` (0: none), so
  // the renderer has holes the crack and error metrics must find.
  std::uint32_t holeEvery = 0;
};

class StacksFullRenderer final : public TerrainRenderer {
 public:
  // Quadrangulates all of `stacks` (finest level) on the GPU; the error says why not.
  static Result<std::unique_ptr<StacksFullRenderer>> create(const StackTerrain& stacks,
                                                            const StacksRenderOptions& options);
  std::string_view name() const override { return "stacks-full"; }
  FrameStats draw(const ViewSetup& view, const RenderSettings& settings) override;
  // The crack metric's open-air test: the mesh, back faces only.
  bool drawLastFrameBackFaces(const ViewSetup& view, const RenderSettings& settings) override;

  std::uint32_t quadCount() const { return pipeline_.indexCount() / 6; }
  std::size_t nodeCount() const { return nodes_; }
  double buildSeconds() const { return buildSeconds_; }
  std::vector<std::string> frameReport() const override;

 private:
  explicit StacksFullRenderer(StackQuadPipelineGpu pipeline) : pipeline_(std::move(pipeline)) {}
  StackQuadPipelineGpu pipeline_;
  FillAndWirePrograms programs_;
  float spacingM_ = 1.0f;  // between stacks (the wireframe's fade)
  StackSkyTexture sky_;    // where imagery is draped
  gl::VertexArray vertexArray_;
  GLenum culledFaces_ = GL_BACK;  // draw(): GL_FRONT for drawLastFrameBackFaces()
  std::size_t nodes_ = 0;
  double buildSeconds_ = 0.0;
  // With holes: the index ranges drawn (glMultiDrawElements), else the indirect draw.
  std::vector<GLsizei> rangeCounts_;
  std::vector<const void*> rangeOffsets_;
};

}  // namespace tellus
