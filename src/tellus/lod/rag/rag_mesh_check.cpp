#include "tellus/lod/rag/rag_mesh_check.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <unordered_map>

namespace tellus::rag {

namespace {

// A vertex position (u, v) by its bits: the midpoints compared are bit-exact by construction.
std::uint64_t positionKey(const Vertex& p) {
  return (std::uint64_t(std::bit_cast<std::uint32_t>(p.x)) << 32) |
         std::uint64_t(std::bit_cast<std::uint32_t>(p.y));
}

}  // namespace

MeshCheck checkMesh(const std::vector<Triangle>& mesh) {
  MeshCheck check;
  check.triangles = mesh.size();
  std::unordered_map<std::uint64_t, float> heightAt;
  heightAt.reserve(mesh.size() * 2);
  for (const Triangle& t : mesh) {
    for (const Vertex& p : t.v) {
      const auto [it, inserted] = heightAt.emplace(positionKey(p), p.z);
      if (!inserted && it->second != p.z) ++check.heightConflicts;
    }
  }
  for (const Triangle& t : mesh) {
    for (int e = 0; e < 3; ++e) {
      const Vertex& a = t.v[std::size_t(e)];
      const Vertex& b = t.v[std::size_t((e + 1) % 3)];
      ++check.edges;
      const Vertex mid = (a + b) * 0.5f;
      const auto it = heightAt.find(positionKey(mid));
      if (it == heightAt.end()) continue;
      ++check.tVertices;
      const float gap = std::abs(it->second - mid.z);
      if (gap > 0.0f) {
        ++check.visibleTVertices;
        check.largestGapM = std::max(check.largestGapM, gap);
      }
    }
  }
  return check;
}

}  // namespace tellus::rag
