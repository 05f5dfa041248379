#pragma once
// 8-bit RGB image in memory and PNG file I/O (stb). Row 0 is the top row.
#include <cstdint>
#include <filesystem>
#include <vector>

#include "tellus/core/result.hpp"

namespace tellus {

struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  // width * height * 3 bytes, row-major, top row first

  RgbImage() = default;
  RgbImage(int w, int h) : width(w), height(h), pixels(size_t(w) * size_t(h) * 3, 0) {}

  std::uint8_t* at(int x, int y) { return &pixels[(size_t(y) * size_t(width) + size_t(x)) * 3]; }
  const std::uint8_t* at(int x, int y) const {
    return &pixels[(size_t(y) * size_t(width) + size_t(x)) * 3];
  }
};

// Writes an RGB PNG atomically: the file appears complete or not at all.
Status writePng(const RgbImage& image, const std::filesystem::path& path);

// The image as JPEG bytes (baseline, quality 1..100).
Result<std::vector<std::uint8_t>> encodeJpeg(const RgbImage& image, int quality);

// Reads any PNG stb understands, converted to 8-bit RGB.
Result<RgbImage> readPng(const std::filesystem::path& path);

}  // namespace tellus
