#include "tellus/lod/clipmaps/clipmap_layout.hpp"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

namespace tellus::clipmaps {
namespace {

// Appends the two triangles of every cell of the local vertex box [min, max] (SW-NE diagonals,
// counter-clockwise seen from above; local y runs south).
void appendGrid(const ClipmapShape& shape, glm::ivec2 min, glm::ivec2 max, std::vector<std::uint32_t>& out) {
  const auto id = [&](int x, int y) { return std::uint32_t(y * shape.n + x); };
  for (int y = min.y; y < max.y; ++y) {
    for (int x = min.x; x < max.x; ++x) {
      // SW = (x, y + 1), SE = (x + 1, y + 1), NE = (x + 1, y), NW = (x, y).
      out.insert(out.end(), {id(x, y + 1), id(x + 1, y + 1), id(x + 1, y)});
      out.insert(out.end(), {id(x, y + 1), id(x + 1, y), id(x, y)});
    }
  }
}

void addPiece(Footprints& f, const ClipmapShape& shape, PieceKind kind,
              const std::vector<std::pair<glm::ivec2, glm::ivec2>>& boxes, glm::ivec2 trim = {0, 0}) {
  Piece piece;
  piece.kind = kind;
  piece.trim = trim;
  piece.firstIndex = std::uint32_t(f.indices.size());
  piece.min = boxes.front().first;
  piece.max = boxes.front().second;
  for (const auto& [min, max] : boxes) {
    appendGrid(shape, min, max, f.indices);
    piece.min = glm::min(piece.min, min);
    piece.max = glm::max(piece.max, max);
  }
  piece.indexCount = std::uint32_t(f.indices.size()) - piece.firstIndex;
  f.pieces.push_back(piece);
}

}  // namespace

Result<ClipmapShape> ClipmapShape::create(int n, int levels) {
  if (n < 31 || n > 1023 || (n + 1) % 4 != 0) {
    return makeError("clipmap size {} is not 4m - 1 in [31, 1023] (31, 35, ..., 255, ..., 1023)", n);
  }
  if (levels < 1 || levels > 24) return makeError("clipmap levels {} outside [1, 24]", levels);
  ClipmapShape shape;
  shape.n = n;
  shape.m = (n + 1) / 4;
  shape.textureSize = n + 1;
  shape.levels = levels;
  shape.transitionWidth = std::clamp(float(n) / 5.0f, 1.0f, shape.maxTransitionWidth());
  return shape;
}

int ClipmapShape::levelsFor(int n, int gridWidth, int gridHeight) {
  const double needed = 2.0 * double(std::max(gridWidth, gridHeight) - 1);
  int levels = 1;
  while (levels < 24 && double(n - 1) * std::ldexp(1.0, levels - 1) < needed) ++levels;
  return levels;
}

std::vector<glm::ivec2> placeLevels(const ClipmapShape& shape, glm::dvec2 viewer) {
  std::vector<glm::ivec2> origins(std::size_t(shape.levels));
  const int halfSpan = (shape.n - 1) / 2;  // 2m - 1: from the origin to the centre
  const int coarsest = shape.levels - 1;
  const glm::dvec2 top = viewer / std::ldexp(1.0, coarsest);
  origins[std::size_t(coarsest)] =
      glm::ivec2(int(std::lround(top.x)), int(std::lround(top.y))) - halfSpan;
  for (int level = coarsest - 1; level >= 0; --level) {
    const glm::dvec2 v = viewer / std::ldexp(1.0, level);
    const glm::ivec2 low = 2 * (origins[std::size_t(level + 1)] + shape.m - 1);
    glm::ivec2 origin = low;
    for (int axis = 0; axis < 2; ++axis) {
      // Trim on the high side (origin = low) or the low side (low + 2): the nearer centre.
      const double lowCentre = double(low[axis] + halfSpan);
      if (std::abs(lowCentre + 2.0 - v[axis]) < std::abs(lowCentre - v[axis])) origin[axis] += 2;
    }
    origins[std::size_t(level)] = origin;
  }
  return origins;
}

glm::ivec2 trimSide(const ClipmapShape& shape, glm::ivec2 coarserOrigin, glm::ivec2 finerOrigin) {
  return finerOrigin / 2 - coarserOrigin - (shape.m - 1);
}

Footprints buildFootprints(const ClipmapShape& shape) {
  Footprints f;
  const int m = shape.m, n = shape.n;
  const int starts[4] = {0, m - 1, 2 * m, 3 * m - 1};
  for (int by = 0; by < 4; ++by) {
    for (int bx = 0; bx < 4; ++bx) {
      if ((bx == 1 || bx == 2) && (by == 1 || by == 2)) continue;  // the hole
      const glm::ivec2 min(starts[bx], starts[by]);
      addPiece(f, shape, PieceKind::Block, {{min, min + (m - 1)}});
    }
  }
  // Fix-ups: 2 cells wide, in the middle of each side.
  addPiece(f, shape, PieceKind::FixUp, {{{2 * m - 2, 0}, {2 * m, m - 1}}});
  addPiece(f, shape, PieceKind::FixUp, {{{2 * m - 2, 3 * m - 1}, {2 * m, n - 1}}});
  addPiece(f, shape, PieceKind::FixUp, {{{0, 2 * m - 2}, {m - 1, 2 * m}}});
  addPiece(f, shape, PieceKind::FixUp, {{{3 * m - 1, 2 * m - 2}, {n - 1, 2 * m}}});
  // The finest level's centre: the whole hole.
  addPiece(f, shape, PieceKind::Centre, {{{m - 1, m - 1}, {3 * m - 1, 3 * m - 1}}});
  // Interior trims: a column on the side the finer level leaves, the full hole's height, and
  // a row beside the finer level.
  for (int ty = 0; ty < 2; ++ty) {
    for (int tx = 0; tx < 2; ++tx) {
      const int columnX = tx == 1 ? m - 1 : 3 * m - 2;
      const int rowY = ty == 1 ? m - 1 : 3 * m - 2;
      const int finerX = m - 1 + tx;
      addPiece(f, shape, PieceKind::Trim,
               {{{columnX, m - 1}, {columnX + 1, 3 * m - 1}},
                {{finerX, rowY}, {finerX + 2 * m - 1, rowY + 1}}},
               {tx, ty});
    }
  }
  // Zero-area triangles along the outer border, every other vertex.
  Piece degenerate;
  degenerate.kind = PieceKind::Degenerate;
  degenerate.min = {0, 0};
  degenerate.max = {n - 1, n - 1};
  degenerate.firstIndex = std::uint32_t(f.indices.size());
  const auto id = [&](int x, int y) { return std::uint32_t(y * n + x); };
  for (int i = 0; i + 2 < n; i += 2) {
    f.indices.insert(f.indices.end(), {id(i, 0), id(i + 1, 0), id(i + 2, 0)});
    f.indices.insert(f.indices.end(), {id(i, n - 1), id(i + 1, n - 1), id(i + 2, n - 1)});
    f.indices.insert(f.indices.end(), {id(0, i), id(0, i + 1), id(0, i + 2)});
    f.indices.insert(f.indices.end(), {id(n - 1, i), id(n - 1, i + 1), id(n - 1, i + 2)});
  }
  degenerate.indexCount = std::uint32_t(f.indices.size()) - degenerate.firstIndex;
  f.pieces.push_back(degenerate);
  return f;
}

std::vector<const Piece*> piecesForLevel(const Footprints& footprints, const ClipmapShape& shape,
                                         int level, glm::ivec2 trim) {
  std::vector<const Piece*> out;
  for (const Piece& piece : footprints.pieces) {
    switch (piece.kind) {
      case PieceKind::Block:
      case PieceKind::FixUp: out.push_back(&piece); break;
      case PieceKind::Centre:
        if (level == 0) out.push_back(&piece);
        break;
      case PieceKind::Trim:
        if (level > 0 && piece.trim == trim) out.push_back(&piece);
        break;
      case PieceKind::Degenerate:
        if (level + 1 < shape.levels) out.push_back(&piece);
        break;
    }
  }
  return out;
}

float blendWeight(const ClipmapShape& shape, glm::ivec2 vertex, glm::dvec2 viewerLevel) {
  const glm::dvec2 d = glm::abs(glm::dvec2(vertex) - viewerLevel);
  const double start = double(shape.blendStart()), w = double(shape.transitionWidth);
  const double a = std::clamp((std::max(d.x, d.y) - start) / w, 0.0, 1.0);
  return float(a);
}

std::vector<SampleRect> exposedRegions(const ClipmapShape& shape, glm::ivec2 from, glm::ivec2 to) {
  const int n = shape.n;
  const glm::ivec2 delta = to - from;
  if (std::abs(delta.x) >= n || std::abs(delta.y) >= n) return {SampleRect{to, to + n}};
  std::vector<SampleRect> out;
  if (delta.x != 0) {  // the new columns, the new window's full height
    SampleRect columns;
    columns.min = {delta.x > 0 ? from.x + n : to.x, to.y};
    columns.max = {delta.x > 0 ? to.x + n : from.x, to.y + n};
    out.push_back(columns);
  }
  if (delta.y != 0) {  // the new rows, over the columns both windows share
    SampleRect rows;
    rows.min = {std::max(from.x, to.x), delta.y > 0 ? from.y + n : to.y};
    rows.max = {std::min(from.x, to.x) + n, delta.y > 0 ? to.y + n : from.y};
    if (!rows.empty()) out.push_back(rows);
  }
  return out;
}

std::vector<ToroidalPiece> wrapToroidally(const SampleRect& rect, int textureSize) {
  std::vector<ToroidalPiece> out;
  if (rect.empty()) return out;
  const glm::ivec2 first = toroidalTexel(rect.min, textureSize);
  const glm::ivec2 size = rect.max - rect.min;
  // Per axis: the part up to the texture's edge, then the rest from texel 0.
  const int splitX = std::min(size.x, textureSize - first.x);
  const int splitY = std::min(size.y, textureSize - first.y);
  const int xs[2][2] = {{0, splitX}, {splitX, size.x}};
  const int ys[2][2] = {{0, splitY}, {splitY, size.y}};
  for (const auto& y : ys) {
    for (const auto& x : xs) {
      if (x[1] <= x[0] || y[1] <= y[0]) continue;
      ToroidalPiece piece;
      piece.samples.min = rect.min + glm::ivec2(x[0], y[0]);
      piece.samples.max = rect.min + glm::ivec2(x[1], y[1]);
      piece.texel = toroidalTexel(piece.samples.min, textureSize);
      out.push_back(piece);
    }
  }
  return out;
}

}  // namespace tellus::clipmaps
