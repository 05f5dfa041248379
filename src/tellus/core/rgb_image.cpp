#include "tellus/core/rgb_image.hpp"

#include <cstddef>
#include <memory>
#include <vector>

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include "tellus/core/atomic_output.hpp"

namespace tellus {

Status writePng(const RgbImage& image, const std::filesystem::path& path) {
  if (image.width <= 0 || image.height <= 0) {
    return makeError("cannot write '{}': empty image", path.string());
  }
  if (Status writable = checkOutputWritable(path); !writable) return writable;
  // Encoded in memory, then written with every write checked: stb's own file writer ignores
  // write errors, so a full disk would leave a truncated PNG reported as written.
  std::vector<std::byte> encoded;
  const auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::byte>*>(context);
    const auto* bytes = static_cast<const std::byte*>(data);
    out->insert(out->end(), bytes, bytes + size);
  };
  if (!stbi_write_png_to_func(append, &encoded, image.width, image.height, 3, image.pixels.data(),
                              image.width * 3)) {
    return makeError("cannot encode PNG '{}'", path.string());
  }
  return writeBytesAtomically(path, encoded);
}

Result<std::vector<std::uint8_t>> encodeJpeg(const RgbImage& image, int quality) {
  if (image.width <= 0 || image.height <= 0 || quality < 1 || quality > 100) {
    return makeError("cannot encode a JPEG of {} x {} at quality {}", image.width, image.height, quality);
  }
  std::vector<std::uint8_t> encoded;
  const auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<std::uint8_t>*>(context);
    const auto* bytes = static_cast<const std::uint8_t*>(data);
    out->insert(out->end(), bytes, bytes + size);
  };
  if (!stbi_write_jpg_to_func(append, &encoded, image.width, image.height, 3, image.pixels.data(), quality)) {
    return makeError("cannot encode a JPEG of {} x {}", image.width, image.height);
  }
  return encoded;
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
