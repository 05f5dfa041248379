#include "tellus/lod/bdam/bdam_exact_leaf.hpp"

#include <algorithm>
#include <array>
#include <limits>

#include <glm/vec2.hpp>

#include "tellus/formats/bdam/bdam_patches.hpp"

namespace tellus::bdam {
namespace {

double orientD(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

}  // namespace

bool northwestEdge(const Triangle& t, glm::ivec2& a, glm::ivec2& b) {
  const std::array<std::array<glm::ivec2, 2>, 3> edges{
      {{t.apex, t.left}, {t.left, t.right}, {t.right, t.apex}}};
  for (const auto& [p, q] : edges) {
    const glm::ivec2 d = q - p;
    if (d.x != 0 && d.y != 0 && (d.x > 0) != (d.y > 0)) {
      a = p;
      b = q;
      return true;
    }
  }
  return false;
}

NodeId nodeAcross(const Triangle& t, glm::ivec2 a, glm::ivec2 b, int level, int domainLog2) {
  const glm::ivec2 third = (t.apex != a && t.apex != b) ? t.apex : (t.left != a && t.left != b) ? t.left : t.right;
  const glm::dvec2 mid = (glm::dvec2(a) + glm::dvec2(b)) * 0.5;
  // Just across the edge: a thousandth of the way from the midpoint away from the third corner.
  // The triangle across (of the same level or coarser) holds that point in its interior.
  const glm::dvec2 q = mid + (mid - glm::dvec2(third)) * 1e-3;
  const double side = double(1 << domainLog2);
  if (q.x <= 0.0 || q.y <= 0.0 || q.x >= side || q.y >= side) return 0;
  NodeId node = q.y < q.x ? 2 : 3;  // root 2 lies south-east of the diagonal
  Triangle cur = nodeTriangle(node, domainLog2);
  for (int l = 0; l < level; ++l) {
    const glm::dvec2 m = (glm::dvec2(cur.left) + glm::dvec2(cur.right)) * 0.5;
    const bool leftSide = (orientD(m, cur.apex, q) > 0.0) == (orientD(m, cur.apex, cur.left) > 0.0);
    const int which = leftSide ? 0 : 1;  // child 0 holds the left corner
    node = 2 * node + NodeId(which);
    cur = cur.child(which);
  }
  return node;
}

ExactLeafMesh exactLeafMesh(const HeightGrid& grid, NodeId leaf, int domainLog2, CutCells cut) {
  const Triangle t = nodeTriangle(leaf, domainLog2);
  const glm::ivec2 lo = t.boxMin(), hi = t.boxMax();
  ExactLeafMesh mesh;
  mesh.origin = glm::uvec2(lo);
  mesh.minZ = std::numeric_limits<float>::max();
  mesh.maxZ = std::numeric_limits<float>::lowest();
  // On or inside the triangle (either winding).
  const auto inside = [&](glm::ivec2 p) {
    const long long u = orient(t.apex, t.left, p), v = orient(t.left, t.right, p), w = orient(t.right, t.apex, p);
    return (u >= 0 && v >= 0 && w >= 0) || (u <= 0 && v <= 0 && w <= 0);
  };
  const int boxWidth = hi.x - lo.x + 1;
  std::vector<int> vertexOf(std::size_t(boxWidth) * std::size_t(hi.y - lo.y + 1), -1);
  const auto vertex = [&](glm::ivec2 p) {
    int& index = vertexOf[std::size_t(p.y - lo.y) * std::size_t(boxWidth) + std::size_t(p.x - lo.x)];
    if (index < 0) {
      index = int(mesh.vertices.size());
      const float h = sampleHeight(grid, p);
      mesh.vertices.push_back({std::uint16_t(p.x - lo.x), std::uint16_t(p.y - lo.y), h});
      mesh.minZ = std::min(mesh.minZ, h);
      mesh.maxZ = std::max(mesh.maxZ, h);
    }
    return std::uint16_t(index);
  };
  const auto emit = [&](glm::ivec2 a, glm::ivec2 b, glm::ivec2 c) {  // counter-clockwise
    mesh.indices.push_back(vertex(a));
    mesh.indices.push_back(vertex(b));
    mesh.indices.push_back(vertex(c));
  };
  const int lastX = std::min(hi.x, grid.width - 1), lastY = std::min(hi.y, grid.height - 1);
  for (int y = lo.y; y < lastY; ++y) {
    for (int x = lo.x; x < lastX; ++x) {
      const glm::ivec2 sw{x, y}, se{x + 1, y}, ne{x + 1, y + 1}, nw{x, y + 1};
      const bool inSw = inside(sw), inSe = inside(se), inNe = inside(ne), inNw = inside(nw);
      const int corners = int(inSw) + int(inSe) + int(inNe) + int(inNw);
      if (corners == 4) {
        emit(sw, se, ne);
        emit(sw, ne, nw);
      } else if (corners == 3 && (!inNw || !inSe)) {
        // Cut along the south-west / north-east diagonal, the reference's own.
        if (!inNw) emit(sw, se, ne);
        else emit(sw, ne, nw);
      } else if (corners == 3) {
        // Cut along the north-west / south-east diagonal.
        if (cut == CutCells::Whole) {
          emit(sw, se, ne);
          emit(sw, ne, nw);
        } else if (cut == CutCells::Half) {
          if (!inSw) emit(se, ne, nw);
          else emit(sw, se, nw);
        }
      }
    }
  }
  if (mesh.vertices.empty()) mesh.minZ = mesh.maxZ = 0.0f;
  return mesh;
}

}  // namespace tellus::bdam
