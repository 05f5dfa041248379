#pragma once
// Georeferenced imagery draped on the spiral globe (seed 001, "High-Resolution Texturing Level
// of Detail"): each image (a Landsat scene, a decal) is an imagery pyramid (dem/
// imagery_pyramid.hpp), paged through memory mapping, drawn as a second pass after the spiral:
// the drawn nodes of its texture quadtree (lod/spiral/texture_quadtree.hpp), each a quad
// tessellated into 10 x 10 cells per 256 texels a side, placed by the spiral's own projection
// and heights (shaders/spiral/imagery.vert), each counted by an occlusion query. The counts
// are read a frame or more late, only when available (the GPU never waits), and drive the
// quadtree's splits and merges; its transfers go to the GPU straight from the mapping. A decal
// is a small image: its quadtree is a node or a few. Needs a current GL 4.5 context.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "tellus/core/camera.hpp"
#include "tellus/core/result.hpp"
#include "tellus/dem/imagery_pyramid.hpp"
#include "tellus/gl/buffer.hpp"
#include "tellus/gl/program.hpp"
#include "tellus/gl/query.hpp"
#include "tellus/gl/texture.hpp"
#include "tellus/gl/vertex_array.hpp"
#include "tellus/lod/spiral/spiral_projection.hpp"
#include "tellus/lod/spiral/texture_quadtree.hpp"

namespace tellus {

struct ImageryOverlayOptions {
  TextureQuadtreeParams quadtree{.maxTransfersPerUpdate = 1};
  int cellsPerTile = 10;    // the seed's 10 x 10 tessellation of a 256-texel quad
  double pull = 0.002;      // drawn this fraction of the distance nearer the eye
  bool showLevels = false;  // tint each node by its texel size (the seed's Figure 15)
};

// What the last update did, summed over the images.
struct ImageryFrameInfo {
  int nodes = 0;            // drawn
  int uploads = 0, evictions = 0, deferred = 0;
  int splits = 0, merges = 0, finerMips = 0, coarserMips = 0;
  int countsRead = 0;       // node counts that arrived
  std::uint64_t residentBytes = 0;
  std::uint64_t uploadBytes = 0;
  double updateMs = 0.0;    // reading the counts, deciding and transferring (render thread)
  double finestTexelM = 0.0;  // the finest drawn texel's size on the ground, metres (0: none)
};

class ImageryOverlay {
 public:
  // One quadtree per pyramid, drawn in order (later ones on top). Errors: shaders.
  static Result<std::unique_ptr<ImageryOverlay>> create(std::vector<ImageryPyramid> images,
                                                        ImageryOverlayOptions options);

  // Reads the counts that arrived (all of them, waiting, when `wait`: stills and tests), lets
  // every quadtree decide, and transfers; then the vertices of every drawn node round the focal
  // point (geodetic radians).
  // `view` gives each node's visible fraction (its grid's points in the view, on the
  // ellipsoid), reported with its count.
  void update(double focusLatRad, double focusLonRad, const ViewSetup& view, bool wait);
  // Draws every drawn node, counting each when `count`. The caller has set the spiral's
  // uniforms (projection, focal point, heights) on program() and bound the height textures.
  void draw(bool count);
  const gl::Program& program() const { return program_; }
  const ImageryFrameInfo& frameInfo() const { return info_; }
  // For tests: the quadtrees.
  const TextureQuadtree& quadtree(std::size_t image) const { return layers_[image]->tree; }
  std::size_t imageCount() const { return layers_.size(); }
  // Whether the last draw's counts have all been read (stills converge on this).
  bool countsPending() const;

 private:
  struct NodeGeometry {
    int cells = 0;
    std::vector<glm::dvec3> normals;  // unit geodetic normals, (cells + 1)^2, row by row
    std::vector<glm::dvec3> ecef;     // the same points on the ellipsoid
    std::vector<glm::vec2> texels;
    double texelM = 0.0;              // a texel's size on the ground, metres
  };
  struct Layer {
    ImageryPyramid pyramid;
    TextureQuadtree tree;
    std::map<QuadTextureId, gl::Texture> textures;
    std::map<QuadTextureId, NodeGeometry> geometry;  // of drawn nodes
    std::vector<QuadDrawnNode> drawn;                // this frame's
    std::vector<GLint> baseVertex;                   // where each drawn node's vertices start
    std::vector<double> visible;                     // each drawn node's fraction in view
  };
  struct IssuedCount {
    std::size_t layer;
    QuadTextureId texture;
    double visible;
    gl::Query query;
  };
  struct FrameCounts {
    std::vector<IssuedCount> issued;
    std::size_t used = 0;
  };

  ImageryOverlay() = default;
  void readCounts(bool wait);
  std::uint64_t upload(Layer& layer, const QuadTextureId& id);
  const NodeGeometry& geometryOf(Layer& layer, const QuadTextureId& id);
  const gl::Buffer& indicesFor(int cells);

  ImageryOverlayOptions options_;
  std::vector<std::unique_ptr<Layer>> layers_;
  gl::Program program_;
  gl::VertexArray vertexArray_;
  gl::Buffer vertices_;
  std::map<int, gl::Buffer> indices_;  // by cells a side
  std::array<FrameCounts, 4> counts_;
  std::uint64_t frame_ = 0;
  ImageryFrameInfo info_;
};

}  // namespace tellus
