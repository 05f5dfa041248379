#pragma once
// A read-back depth buffer: reversed-Z depth per pixel (1 at the near plane, towards 0 far
// away; exactly 0 where nothing was drawn), row 0 = top.
#include <cstddef>
#include <vector>

namespace tellus {

struct DepthImage {
  int width = 0;
  int height = 0;
  std::vector<float> depth;
  float at(int x, int y) const {
    return depth[std::size_t(y) * std::size_t(width) + std::size_t(x)];
  }
};

}  // namespace tellus
