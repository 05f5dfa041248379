#include "tellus/render/spiral/imagery_overlay.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <spdlog/spdlog.h>

#include "tellus/core/stopwatch.hpp"
#include "tellus/core/geodesy.hpp"

namespace tellus {
namespace {

constexpr double kEarthRadiusM = 6'371'000.0;

struct DrapeVertex {
  float dirX, dirY, radius;  // from the focal point, as the spiral's vertices
  float u, v;
};

glm::dvec3 unitNormal(double latRad, double lonRad) {
  return {std::cos(latRad) * std::cos(lonRad), std::cos(latRad) * std::sin(lonRad), std::sin(latRad)};
}

// A colour per mip level of the texture, finest first (the seed's level colours).
glm::vec3 levelColour(int mip) {
  static const glm::vec3 colours[] = {{0.9f, 0.1f, 0.1f}, {1.0f, 0.6f, 0.0f}, {0.95f, 0.9f, 0.1f},
                                      {0.2f, 0.8f, 0.2f}, {0.1f, 0.8f, 0.9f}, {0.2f, 0.3f, 1.0f},
                                      {0.6f, 0.2f, 0.9f}, {0.9f, 0.3f, 0.8f}};
  return colours[std::clamp(mip, 0, 7)];
}

}  // namespace

Result<std::unique_ptr<ImageryOverlay>> ImageryOverlay::create(std::vector<ImageryPyramid> images,
                                                               ImageryOverlayOptions options) {
  if (options.cellsPerTile < 1 || options.cellsPerTile > 64) {
    return makeError("imagery: 1 to 64 cells a tile side, got {}", options.cellsPerTile);
  }
  if (!(options.pull >= 0.0 && options.pull < 0.1)) {
    return makeError("imagery: the pull towards the eye must be in [0, 0.1), got {}", options.pull);
  }
  std::unique_ptr<ImageryOverlay> o(new ImageryOverlay());
  o->options_ = options;
  for (ImageryPyramid& image : images) {
    const ImageryLayout layout{image.width(), image.height(), image.tileSize(), image.levels()};
    // Every node's texture must fit, with the four children of a split beside it.
    const std::uint64_t largest =
        quadTextureBytes(layout, {{std::min(options.quadtree.leafLevel, layout.levels - 1), 0, 0}, 0});
    if (options.quadtree.memoryBudgetBytes < 6 * largest) {
      return makeError("imagery '{}': a memory budget of {} MiB holds too few of its textures "
                       "(at least {} MiB)",
                       image.path().string(), options.quadtree.memoryBudgetBytes >> 20,
                       (6 * largest + (1 << 20) - 1) >> 20);
    }
    auto layer = std::unique_ptr<Layer>(new Layer{std::move(image), TextureQuadtree(layout, options.quadtree), {}, {}, {}, {}, {}});
    o->layers_.push_back(std::move(layer));
  }
  Result<gl::Program> program = gl::Program::fromFiles(
      {{GL_VERTEX_SHADER, "spiral/imagery.vert"}, {GL_FRAGMENT_SHADER, "spiral/imagery.frag"}});
  if (!program) return program.error();
  o->program_ = std::move(program.value());
  o->vertexArray_ = gl::VertexArray::create();
  const GLuint vao = o->vertexArray_.id();
  glEnableVertexArrayAttrib(vao, 0);
  glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vao, 0, 0);
  glEnableVertexArrayAttrib(vao, 1);
  glVertexArrayAttribFormat(vao, 1, 2, GL_FLOAT, GL_FALSE, 3 * sizeof(float));
  glVertexArrayAttribBinding(vao, 1, 0);
  return o;
}

bool ImageryOverlay::countsPending() const {
  for (const FrameCounts& c : counts_) {
    if (c.used > 0) return true;
  }
  return false;
}

void ImageryOverlay::readCounts(bool wait) {
  GLint samples = 1;
  glGetIntegerv(GL_SAMPLES, &samples);
  const std::uint64_t perPixel = std::uint64_t(std::max(samples, 1));
  // Oldest first, so a newer count for a node overrides an older one.
  for (std::uint64_t age = counts_.size(); age >= 1; --age) {
    if (frame_ < age) continue;
    FrameCounts& c = counts_[std::size_t((frame_ - age) % counts_.size())];
    if (c.used == 0) continue;
    if (!wait && !c.issued[c.used - 1].query.available()) continue;  // in order: the last is last
    for (std::size_t k = 0; k < c.used; ++k) {
      const IssuedCount& issued = c.issued[k];
      layers_[issued.layer]->tree.reportPixels(issued.texture.node, issued.texture.mip,
                                               issued.query.result() / perPixel, issued.visible);
    }
    info_.countsRead += int(c.used);
    c.used = 0;
  }
}

std::uint64_t ImageryOverlay::upload(Layer& layer, const QuadTextureId& id) {
  const ImageryPyramid& p = layer.pyramid;
  const ImageryLayout& layout = layer.tree.layout();
  const QuadTextureRect r = quadTextureRect(layout, id);
  // The mip chain comes from the pyramid's coarser levels, not from the GPU (no mipmap
  // generation, which waits for the GPU on some drivers): mip k is level id.mip + k.
  const int fullChain = 1 + int(std::floor(std::log2(double(std::max(r.width(), r.height())))));
  const int mips = std::min(fullChain, p.levels() - id.mip);
  gl::Texture texture = gl::Texture::create2D(GL_RGBA8, r.width(), r.height(), mips);
  const int t = p.tileSize();
  glPixelStorei(GL_UNPACK_ROW_LENGTH, t);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  std::uint64_t bytes = 0;
  for (int k = 0; k < mips; ++k) {
    const int level = id.mip + k;
    // The texture's level k (GL's size: halved, rounded down) over the level's texels.
    const int w = std::max(1, r.width() >> k), h = std::max(1, r.height() >> k);
    const int x0 = r.x0 >> k, y0 = r.y0 >> k;
    const int x1 = std::min(x0 + w, layout.levelWidth(level)), y1 = std::min(y0 + h, layout.levelHeight(level));
    // Each tile's part, straight from the mapping.
    for (int ty = y0 / t; ty * t < y1; ++ty) {
      for (int tx = x0 / t; tx * t < x1; ++tx) {
        const int sx = std::max(x0, tx * t), sy = std::max(y0, ty * t);
        const int ex = std::min(x1, (tx + 1) * t), ey = std::min(y1, (ty + 1) * t);
        const std::byte* tile = p.tile(level, tx, ty).data();
        const std::byte* first = tile + (std::size_t(sy - ty * t) * t + std::size_t(sx - tx * t)) * 4;
        texture.upload2D(k, sx - x0, sy - y0, ex - sx, ey - sy, GL_RGBA, GL_UNSIGNED_BYTE, first);
        bytes += std::uint64_t(ex - sx) * std::uint64_t(ey - sy) * 4;
      }
    }
  }
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  texture.setFilter(mips > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR, GL_LINEAR);
  texture.setWrap(GL_CLAMP_TO_EDGE);
  layer.textures[id] = std::move(texture);
  return bytes;
}

const ImageryOverlay::NodeGeometry& ImageryOverlay::geometryOf(Layer& layer, const QuadTextureId& id) {
  auto found = layer.geometry.find(id);
  if (found != layer.geometry.end()) return found->second;
  const ImageryPyramid& p = layer.pyramid;
  const QuadTextureRect r = quadTextureRect(layer.tree.layout(), id);
  NodeGeometry g;
  const int tilesAcross = (std::max(r.width(), r.height()) + p.tileSize() - 1) / p.tileSize();
  g.cells = options_.cellsPerTile * tilesAcross;
  const double scale = double(1 << id.mip);  // level-0 texels a texel of this mip
  for (int j = 0; j <= g.cells; ++j) {
    for (int i = 0; i <= g.cells; ++i) {
      const double u = double(i) / g.cells, v = double(j) / g.cells;
      const double x = (r.x0 + u * r.width()) * scale, y = (r.y0 + v * r.height()) * scale;
      Result<ImageryPyramid::LatLon> at = p.latLonAt(std::min(x, double(p.width())),
                                                     std::min(y, double(p.height())));
      const ImageryPyramid::LatLon ll = at ? at.value() : ImageryPyramid::LatLon{};
      g.normals.push_back(unitNormal(ll.latDeg * wgs84::kDegree, ll.lonDeg * wgs84::kDegree));
      g.ecef.push_back(wgs84::geodeticToEcef({ll.latDeg * wgs84::kDegree, ll.lonDeg * wgs84::kDegree, 0.0}));
      g.texels.push_back({float(u), float(v)});
    }
  }
  const double across = std::acos(std::clamp(glm::dot(g.normals.front(), g.normals[std::size_t(g.cells)]), -1.0, 1.0));
  g.texelM = across * kEarthRadiusM / r.width();
  return layer.geometry.emplace(id, std::move(g)).first->second;
}

const gl::Buffer& ImageryOverlay::indicesFor(int cells) {
  auto found = indices_.find(cells);
  if (found != indices_.end()) return found->second;
  std::vector<std::uint32_t> indices;
  const auto at = [cells](int i, int j) { return std::uint32_t(j * (cells + 1) + i); };
  for (int j = 0; j < cells; ++j) {
    for (int i = 0; i < cells; ++i) {
      indices.insert(indices.end(), {at(i, j), at(i, j + 1), at(i + 1, j), at(i + 1, j),
                                     at(i, j + 1), at(i + 1, j + 1)});
    }
  }
  return indices_.emplace(cells, gl::Buffer(std::span<const std::uint32_t>(indices))).first->second;
}

void ImageryOverlay::update(double focusLatRad, double focusLonRad, const ViewSetup& view,
                            bool wait) {
  const Stopwatch start;
  info_ = {};
  readCounts(wait);
  for (std::unique_ptr<Layer>& layer : layers_) {
    const QuadtreeUpdate changes = layer->tree.update(wait);
    for (const QuadTextureId& id : changes.evictions) layer->textures.erase(id);
    for (const QuadTextureId& id : changes.uploads) info_.uploadBytes += upload(*layer, id);
    info_.uploads += int(changes.uploads.size());
    info_.evictions += int(changes.evictions.size());
    info_.deferred += changes.deferred;
    info_.splits += changes.splits;
    info_.merges += changes.merges;
    info_.finerMips += changes.finerMips;
    info_.coarserMips += changes.coarserMips;
    info_.residentBytes += layer->tree.residentBytes();
  }
  info_.updateMs = start.elapsedMs();
  spdlog::debug("imagery: {} counts read, {} uploads, {} evictions, {} deferred, splits {}, "
                "merges {}, mips +{} -{}, {:.1f} MiB resident, {:.2f} ms",
                info_.countsRead, info_.uploads, info_.evictions, info_.deferred, info_.splits,
                info_.merges, info_.finerMips, info_.coarserMips,
                double(info_.residentBytes) / double(1 << 20), info_.updateMs);

  // The drawn nodes' vertices round the focal point, in double.
  const glm::dvec3 f = unitNormal(focusLatRad, focusLonRad);
  const glm::dvec3 east(-std::sin(focusLonRad), std::cos(focusLonRad), 0.0);
  const glm::dvec3 north = glm::cross(f, east);
  std::vector<DrapeVertex> vertices;
  for (std::unique_ptr<Layer>& layer : layers_) {
    layer->drawn = layer->tree.drawn();
    layer->baseVertex.clear();
    layer->visible.clear();
    std::map<QuadTextureId, NodeGeometry> kept;
    for (const QuadDrawnNode& node : layer->drawn) {
      const QuadTextureId id{node.id, node.mip};
      const NodeGeometry& g = geometryOf(*layer, id);
      layer->baseVertex.push_back(GLint(vertices.size()));
      for (std::size_t k = 0; k < g.normals.size(); ++k) {
        const glm::dvec3 d = g.normals[k] - f;
        const double radius = 2.0 * std::asin(std::min(1.0, 0.5 * glm::length(d)));
        const double de = glm::dot(d, east), dn = glm::dot(d, north);
        const double h = std::sqrt(de * de + dn * dn);
        const glm::dvec2 direction = h > 0.0 ? glm::dvec2(de, dn) / h : glm::dvec2(0.0, 1.0);
        vertices.push_back({float(direction.x), float(direction.y), float(radius), g.texels[k].x,
                            g.texels[k].y});
      }
      // The fraction of the grid's points in view (on the ellipsoid: heights move a point by a
      // few kilometres at most).
      std::size_t inside = 0;
      for (const glm::dvec3& p : g.ecef) {
        const glm::dvec4 clip = view.relativeViewProjection() * glm::dvec4(p - view.camera.position, 1.0);
        inside += clip.w > 0.0 && std::abs(clip.x) <= clip.w && std::abs(clip.y) <= clip.w ? 1 : 0;
      }
      layer->visible.push_back(double(std::max<std::size_t>(inside, 1)) / double(g.ecef.size()));
      info_.finestTexelM = info_.finestTexelM > 0.0 ? std::min(info_.finestTexelM, g.texelM) : g.texelM;
      ++info_.nodes;
    }
    // Forget the geometry of nodes no longer drawn.
    for (const QuadDrawnNode& node : layer->drawn) {
      const QuadTextureId id{node.id, node.mip};
      kept.emplace(id, std::move(layer->geometry.at(id)));
    }
    layer->geometry = std::move(kept);
  }
  const std::size_t bytes = vertices.size() * sizeof(DrapeVertex);
  if (bytes > vertices_.size()) {
    vertices_ = gl::Buffer(std::max(bytes, vertices_.size() * 2), nullptr, GL_DYNAMIC_STORAGE_BIT);
    glVertexArrayVertexBuffer(vertexArray_.id(), 0, vertices_.id(), 0, sizeof(DrapeVertex));
  }
  if (bytes > 0) vertices_.upload(0, bytes, vertices.data());
}

void ImageryOverlay::draw(bool count) {
  FrameCounts& counts = counts_[std::size_t(frame_ % counts_.size())];
  if (count) counts.used = 0;  // counts never read in four frames are dropped
  GLint depthFunc = GL_LESS;
  GLboolean depthMask = GL_TRUE;
  glGetIntegerv(GL_DEPTH_FUNC, &depthFunc);
  glGetBooleanv(GL_DEPTH_WRITEMASK, &depthMask);
  const GLboolean blend = glIsEnabled(GL_BLEND);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  // Nearer or as near as the terrain, whichever way depth runs (Tellus: reversed, GL_GREATER).
  glDepthFunc(depthFunc == GL_GREATER || depthFunc == GL_GEQUAL ? GL_GEQUAL : GL_LEQUAL);
  glDepthMask(GL_FALSE);
  program_.use();
  vertexArray_.bind();
  program_.set("uImage", 5);
  program_.set("uLevelTint", options_.showLevels ? 0.45f : 0.0f);
  for (std::size_t l = 0; l < layers_.size(); ++l) {
    Layer& layer = *layers_[l];
    program_.set("uPull", float(options_.pull * double(l + 1)));  // later images on top
    for (std::size_t k = 0; k < layer.drawn.size(); ++k) {
      const QuadTextureId id{layer.drawn[k].id, layer.drawn[k].mip};
      const NodeGeometry& g = layer.geometry.at(id);
      layer.textures.at(id).bindUnit(5);
      program_.set("uTint", levelColour(id.mip));
      glVertexArrayElementBuffer(vertexArray_.id(), indicesFor(g.cells).id());
      if (count) {
        if (counts.used == counts.issued.size()) {
          counts.issued.push_back({l, id, 1.0, gl::Query::create(GL_SAMPLES_PASSED)});
        }
        IssuedCount& issued = counts.issued[counts.used++];
        issued.layer = l;
        issued.texture = id;
        issued.visible = layer.visible[k];
        issued.query.begin();
      }
      glDrawElementsBaseVertex(GL_TRIANGLES, 6 * g.cells * g.cells, GL_UNSIGNED_INT, nullptr,
                               layer.baseVertex[k]);
      if (count) counts.issued[counts.used - 1].query.end();
    }
  }
  glDepthMask(depthMask);
  glDepthFunc(GLenum(depthFunc));
  if (!blend) glDisable(GL_BLEND);
  if (count) ++frame_;
}

}  // namespace tellus
