#include "tellus/formats/stacks/stack_mesh_check.hpp"

#include <array>
#include <bit>
#include <map>
#include <unordered_map>

namespace tellus {
namespace {

struct PositionKey {
  std::array<std::uint32_t, 3> bits;
  bool operator==(const PositionKey&) const = default;
};
struct PositionHash {
  std::size_t operator()(const PositionKey& k) const {
    return std::size_t(k.bits[0]) * 73856093u ^ std::size_t(k.bits[1]) * 19349663u ^
           std::size_t(k.bits[2]) * 83492791u;
  }
};

}  // namespace

StackMeshCheck checkStackMesh(const StackMesh& mesh) {
  // Weld: neighbouring nodes compute a shared cell's vertex from the same densities, so its
  // copies are bit for bit equal.
  std::unordered_map<PositionKey, std::uint32_t, PositionHash> ids;
  std::vector<std::uint32_t> welded(mesh.vertices.size());
  for (std::size_t v = 0; v < mesh.vertices.size(); ++v) {
    const auto& p = mesh.vertices[v].position;
    const PositionKey key{{std::bit_cast<std::uint32_t>(p[0]), std::bit_cast<std::uint32_t>(p[1]),
                           std::bit_cast<std::uint32_t>(p[2])}};
    welded[v] = ids.try_emplace(key, std::uint32_t(ids.size())).first->second;
  }
  StackMeshCheck check;
  check.vertices = ids.size();
  std::unordered_map<std::uint64_t, int> directed;  // a << 32 | b -> uses
  for (std::size_t q = 0; q + 6 <= mesh.indices.size(); q += 6) {
    const std::array<std::uint32_t, 4> v{welded[mesh.indices[q]], welded[mesh.indices[q + 1]],
                                         welded[mesh.indices[q + 2]], welded[mesh.indices[q + 5]]};
    ++check.quads;
    if (v[0] == v[1] || v[0] == v[2] || v[0] == v[3] || v[1] == v[2] || v[1] == v[3] ||
        v[2] == v[3]) {
      ++check.degenerateQuads;
    }
    for (int e = 0; e < 4; ++e) {
      const std::uint64_t a = v[std::size_t(e)], b = v[std::size_t((e + 1) % 4)];
      ++directed[a << 32 | b];
    }
  }
  for (const auto& [key, uses] : directed) {
    const std::uint64_t a = key >> 32, b = key & 0xffffffffu;
    const auto reverse = directed.find(b << 32 | a);
    const int back = reverse == directed.end() ? 0 : reverse->second;
    if (a < b || back == 0) {
      ++check.edges;  // counted once, from its smaller end (or alone)
      if (uses + back > 2) ++check.nonManifoldEdges;
    }
    if (uses > back) ++check.unbalancedEdges;
  }
  return check;
}

}  // namespace tellus
