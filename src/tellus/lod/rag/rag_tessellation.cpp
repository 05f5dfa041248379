#include "tellus/lod/rag/rag_tessellation.hpp"

namespace tellus::rag {

std::uint32_t tessellationCase(Variant variant, std::uint32_t needed) {
  needed &= 7u;
  if (variant == Variant::RightAngled && (needed & (kEdge01 | kEdge02)) != 0) {
    needed |= kEdge12;
  }
  return needed;
}

namespace {

// The midpoint of a -> b: position (a + b) * 0.5, height from the map (moved `surface` of the
// way there from the interpolated height; 1: the map's exactly) or interpolated.
Vertex midpoint(const Vertex& a, const Vertex& b, bool fromMap, const HeightGrid& grid,
                float surface, MapSampling sampling) {
  Vertex m = (a + b) * 0.5f;
  if (!fromMap) return m;
  const float mapHeight = sampleMap(grid, m.x, m.y, sampling);
  m.z = surface >= 1.0f ? mapHeight : m.z + surface * (mapHeight - m.z);
  return m;
}

}  // namespace

Tessellation tessellate(const Triangle& triangle, std::uint32_t needed, Variant variant,
                        const HeightGrid& grid, bool emitFill, const EdgeSurface& surface,
                        MapSampling sampling) {
  const std::uint32_t tess = tessellationCase(variant, needed);
  const Vertex& v0 = triangle.v[0];
  const Vertex& v1 = triangle.v[1];
  const Vertex& v2 = triangle.v[2];
  // Only the midpoints the case uses are computed (and sampled), as in the shader.
  const auto m01 = [&] { return midpoint(v0, v1, true, grid, surface[0], sampling); };
  const auto m12 = [&] { return midpoint(v1, v2, (needed & kEdge12) != 0, grid, surface[1], sampling); };
  const auto m02 = [&] { return midpoint(v0, v2, true, grid, surface[2], sampling); };

  Tessellation out;
  const auto emit = [&out](const Vertex& a, const Vertex& b, const Vertex& c) {
    out.triangles[std::size_t(out.count++)] = Triangle{{a, b, c}};
  };
  switch (tess) {
    case 0:
      emit(v0, v1, v2);
      break;
    case kEdge01: {  // oblique only: the leg's midpoint joined to v2
      const Vertex a = m01();
      emit(v0, a, v2);
      emit(a, v1, v2);
      break;
    }
    case kEdge02: {  // oblique only: the leg's midpoint joined to v1
      const Vertex c = m02();
      emit(v0, v1, c);
      emit(c, v1, v2);
      break;
    }
    case kEdge01 | kEdge02: {  // oblique only: both legs, the quad cut from m01 to v2
      const Vertex a = m01(), c = m02();
      emit(v0, a, c);
      emit(a, v1, v2);
      emit(c, a, v2);
      break;
    }
    case kEdge12: {  // bisection of the hypotenuse
      const Vertex b = m12();
      emit(b, v0, v1);
      emit(b, v2, v0);
      break;
    }
    case kEdge12 | kEdge01: {  // bisection, then the half on v0-v1 bisected again
      const Vertex a = m01(), b = m12();
      emit(a, b, v0);
      emit(a, v1, b);
      emit(b, v2, v0);
      break;
    }
    case kEdge12 | kEdge02: {  // bisection, then the half on v0-v2 bisected again
      const Vertex b = m12(), c = m02();
      emit(b, v0, v1);
      emit(c, b, v2);
      emit(c, v0, b);
      break;
    }
    default: {  // all three: both halves bisected again
      const Vertex a = m01(), b = m12(), c = m02();
      emit(a, b, v0);
      emit(a, v1, b);
      emit(c, b, v2);
      emit(c, v0, b);
      break;
    }
  }
  if ((tess & kEdge12) != 0 && (needed & kEdge12) == 0 && emitFill) emit(v1, m12(), v2);
  return out;
}

}  // namespace tellus::rag
