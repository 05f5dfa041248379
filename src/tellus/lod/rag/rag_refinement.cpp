#include "tellus/lod/rag/rag_refinement.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include <glm/geometric.hpp>

namespace tellus::rag {

RefinementView RefinementView::create(const ViewSetup& view, double spacingXM, double spacingYM,
                                      HeightRange heights, float verticalExaggeration) {
  RefinementView out;
  out.clipFromRelative = glm::mat4(view.relativeViewProjection());
  const glm::dvec3& eye = view.camera.position;
  // World x = u * spacingX, y = v * spacingY, z = h * exaggeration (height_grid.hpp).
  out.cameraGrid = glm::vec3(float(eye.x / spacingXM), float(eye.y / spacingYM),
                             float(eye.z / double(verticalExaggeration)));
  out.gridScale = glm::vec3(float(spacingXM), float(spacingYM), verticalExaggeration);
  out.viewportPx = glm::vec2(float(view.width), float(view.height));
  // The projection's y scale is 1 / tan(fovY / 2): half the height in pixels times it.
  out.focalPx = float(0.5 * double(view.height) * view.projection[1][1]);
  out.nearM = float(view.clip.nearM);
  out.farM = float(view.clip.farM);
  out.minHeightM = heights.minM;
  out.maxHeightM = heights.maxM;
  return out;
}

glm::vec4 clipPosition(const RefinementView& view, const Vertex& vertex) {
  const glm::vec3 relative = (vertex - view.cameraGrid) * view.gridScale;
  return view.clipFromRelative * glm::vec4(relative, 1.0f);
}

namespace {

glm::vec2 toPixels(const RefinementView& view, const glm::vec4& clip) {
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  return (ndc * 0.5f + 0.5f) * view.viewportPx;
}

// The edge's ends in a canonical order (by u, then v), so both triangles sharing the edge
// compute the same thing in the same order.
std::pair<Vertex, Vertex> canonical(const Vertex& a, const Vertex& b) {
  if (a.x < b.x || (a.x == b.x && a.y < b.y)) return {a, b};
  return {b, a};
}

// A single cell's north-west to south-east diagonal (ends in canonical order), which the
// reference's surface crosses at the cell's centre.
bool crossesReferenceDiagonal(const RefinementSettings& settings, const Vertex& a,
                              const Vertex& b) {
  return settings.sampling == MapSampling::Surface && b.x - a.x == 1.0f && a.y - b.y == 1.0f;
}

}  // namespace

EdgeMeasure measureEdge(const RefinementView& view, const RefinementSettings& settings,
                        const HeightGrid& grid, const Vertex& a0, const Vertex& b0) {
  const auto [a, b] = canonical(a0, b0);
  EdgeMeasure m;
  if (std::abs(a.x - b.x) <= 1.0f && std::abs(a.y - b.y) <= 1.0f &&
      !crossesReferenceDiagonal(settings, a, b)) {
    m.decided = true;
    m.split = false;
    return m;
  }
  if (settings.variant == Variant::Oblique) {
    const Vertex interpolated = (a + b) * 0.5f;
    Vertex fromMap = interpolated;
    fromMap.z = sampleMap(grid, interpolated.x, interpolated.y, settings.sampling);
    const glm::vec4 ci = clipPosition(view, interpolated);
    const glm::vec4 cm = clipPosition(view, fromMap);
    if (ci.w <= view.nearM || cm.w <= view.nearM) {
      m.decided = true;
      m.split = true;
      return m;
    }
    if (settings.edgeLengthPx > 0.0f) {
      const glm::vec3 span = (b - a) * view.gridScale;
      const glm::vec3 toMidpoint = (interpolated - view.cameraGrid) * view.gridScale;
      m.lengthPx = glm::length(span) * view.focalPx / glm::length(toMidpoint);
      m.lengthThresholdPx = settings.edgeLengthPx;
      if (m.lengthPx >= m.lengthThresholdPx) {
        m.split = true;
        return m;  // decided by its length (surface 1: the map's height at once)
      }
    }
    m.value = glm::length(toPixels(view, cm) - toPixels(view, ci));
    if (settings.edgeProbes >= 3) {
      for (int k = 1; k <= 3; k += 2) {  // the quarter points (a point behind the eye adds nothing)
        const Vertex q = a + (b - a) * (0.25f * float(k));
        Vertex qm = q;
        qm.z = sampleMap(grid, q.x, q.y, settings.sampling);
        const glm::vec4 cq = clipPosition(view, q), cqm = clipPosition(view, qm);
        if (cq.w > view.nearM && cqm.w > view.nearM) {
          m.value = std::max(m.value, glm::length(toPixels(view, cqm) - toPixels(view, cq)));
        }
      }
    }
    m.threshold = settings.pixelEdge;
    if (settings.morphBand > 0.0f) {
      const float past = (m.value - m.threshold) / (m.threshold * settings.morphBand);
      m.surface = std::clamp(past, 0.0f, 1.0f);
    }
  } else {
    // Linear depth of the nearer end, 0 at the near plane and 1 at the far plane.
    const float w = std::min(clipPosition(view, a).w, clipPosition(view, b).w);
    const float depth = std::clamp((w - view.nearM) / (view.farM - view.nearM), 0.0f, 1.0f);
    const float weight = settings.depthDetail + (1.0f - settings.depthDetail) * (1.0f - depth);
    m.value = std::abs(a.z - b.z) * weight;
    m.threshold = settings.heightDifferenceM;
  }
  // The shader's step(threshold, value) for Oblique (split at >=); strictly greater for the
  // height difference, so a flat map with threshold 0 splits nothing.
  m.split = settings.variant == Variant::Oblique ? m.value >= m.threshold : m.value > m.threshold;
  return m;
}

bool edgeNeedsSplit(const RefinementView& view, const RefinementSettings& settings,
                    const HeightGrid& grid, const Vertex& a, const Vertex& b) {
  return measureEdge(view, settings, grid, a, b).split;
}

std::uint32_t neededEdges(const RefinementView& view, const RefinementSettings& settings,
                          const HeightGrid& grid, const Triangle& t, float* closestDecision,
                          EdgeSurface* surface) {
  static constexpr std::array<std::pair<std::size_t, std::size_t>, 3> kEnds{
      {{0, 1}, {1, 2}, {0, 2}}};  // bit 0: v0-v1, bit 1: v1-v2, bit 2: v0-v2
  std::uint32_t bits = 0;
  for (std::uint32_t e = 0; e < 3; ++e) {
    const EdgeMeasure m = measureEdge(view, settings, grid, t.v[kEnds[e].first],
                                      t.v[kEnds[e].second]);
    if (m.split) bits |= 1u << e;
    if (surface != nullptr) (*surface)[e] = m.surface;
    if (closestDecision != nullptr && !m.decided && m.threshold > 0.0f) {
      *closestDecision =
          std::min(*closestDecision, std::abs(m.value - m.threshold) / m.threshold);
    }
    if (closestDecision != nullptr && m.lengthThresholdPx > 0.0f) {
      *closestDecision = std::min(
          *closestDecision, std::abs(m.lengthPx - m.lengthThresholdPx) / m.lengthThresholdPx);
    }
  }
  return bits;
}

bool fillIsSafe(const RefinementView& view, const Vertex& a, const Vertex& b) {
  return clipPosition(view, a).w > view.nearM && clipPosition(view, b).w > view.nearM;
}

bool isOutsideFrustum(const RefinementView& view, const Triangle& t) {
  // Outside a plane: x < -w, x > w, y < -w, y > w, z < 0 (beyond far), z > w (nearer than
  // near), with the reversed-Z [0, 1] depth of camera.hpp.
  std::array<bool, 6> allOutside{true, true, true, true, true, true};
  for (const Vertex& corner : t.v) {
    for (const float h : {view.minHeightM, view.maxHeightM}) {
      const glm::vec4 c = clipPosition(view, Vertex(corner.x, corner.y, h));
      const float margin = kClipMargin * std::abs(c.w);
      allOutside[0] = allOutside[0] && c.x < -c.w - margin;
      allOutside[1] = allOutside[1] && c.x > c.w + margin;
      allOutside[2] = allOutside[2] && c.y < -c.w - margin;
      allOutside[3] = allOutside[3] && c.y > c.w + margin;
      allOutside[4] = allOutside[4] && c.z < -margin;
      allOutside[5] = allOutside[5] && c.z > c.w + margin;
    }
  }
  return std::any_of(allOutside.begin(), allOutside.end(), [](bool b) { return b; });
}

RefinementResult refine(const std::vector<Triangle>& mesh, const HeightGrid& grid,
                        const RefinementView& view, const RefinementSettings& settings,
                        int passes) {
  RefinementResult result;
  result.triangles = mesh;
  for (int pass = 0; pass < passes; ++pass) {
    PassStats stats;
    stats.input = result.triangles.size();
    std::vector<Triangle> next;
    next.reserve(result.triangles.size() * 2);
    for (const Triangle& t : result.triangles) {
      if (settings.earlyClip && isOutsideFrustum(view, t)) {
        ++stats.clipped;
        continue;
      }
      EdgeSurface surface{1.0f, 1.0f, 1.0f};
      const std::uint32_t needed =
          neededEdges(view, settings, grid, t, &result.closestDecision, &surface);
      const Tessellation tess = tessellate(t, needed, settings.variant, grid,
                                           fillIsSafe(view, t.v[1], t.v[2]), surface,
                                           settings.sampling);
      next.insert(next.end(), tess.triangles.begin(), tess.triangles.begin() + tess.count);
    }
    stats.output = next.size();
    result.passes.push_back(stats);
    result.triangles = std::move(next);
  }
  return result;
}

}  // namespace tellus::rag
