#pragma once
// Index buffers of regular vertex grids (row-major, row 0 first), two triangles a cell with the
// diagonal from the north-east to the south-west vertex, one buffer per grid size, shared by
// every chunk of that size. Buffers stay at the same address (chunks keep pointers to them).
// Needs a current GL 4.5 context for its whole life.
#include <map>
#include <utility>

#include "tellus/gl/buffer.hpp"

namespace tellus {

class GridIndexBuffers {
 public:
  const gl::Buffer& forGrid(int vertsX, int vertsY);

 private:
  std::map<std::pair<int, int>, gl::Buffer> buffers_;  // node-stable
};

}  // namespace tellus
