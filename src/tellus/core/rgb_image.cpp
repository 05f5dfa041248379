#include "tellus/core/rgb_image.hpp"

#include <memory>

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include "tellus/core/atomic_output.hpp"

namespace tellus {

Status writePng(const RgbImage& image, const std::filesystem::path& path) {
  if (image.width <= 0 || image.height <= 0) {
    return makeError("cannot write '{}': empty image", path.string());
  }
  return writeFileAtomically(path, [&](const std::filesystem::path& temp) -> Status {
    if (!stbi_write_png(temp.c_str(), image.width, image.height, 3, image.pixels.data(),
                        image.width * 3)) {
      return makeError("cannot write PNG '{}'", path.string());
    }
    return {};
  });
}

Result<RgbImage> readPng(const std::filesystem::path& path) {
  int w = 0, h = 0, channels = 0;
  std::unique_ptr<stbi_uc, decltype(&stbi_image_free)> data(
      stbi_load(path.c_str(), &w, &h, &channels, 3), &stbi_image_free);
  if (!data) {
    return makeError("cannot read image '{}': {}", path.string(), stbi_failure_reason());
  }
  RgbImage image(w, h);
  std::copy_n(data.get(), image.pixels.size(), image.pixels.begin());
  return image;
}

}  // namespace tellus
