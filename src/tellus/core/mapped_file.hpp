#pragma once
// A file mapped read-only into memory (POSIX mmap): pages come from the file as they are
// touched, so a large file costs address space, not memory, and its bytes can go straight to
// the GPU without a copy into a buffer of our own (seed 001's paging of its texture quadtree).
#include <cstddef>
#include <filesystem>
#include <span>

#include "tellus/core/result.hpp"

namespace tellus {

class MappedFile {
 public:
  MappedFile() = default;
  ~MappedFile();
  MappedFile(MappedFile&& other) noexcept;
  MappedFile& operator=(MappedFile&& other) noexcept;
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  // Errors name the file: missing, not a regular file, empty, or not mappable.
  static Result<MappedFile> open(const std::filesystem::path& path);

  std::span<const std::byte> bytes() const { return {data_, size_}; }
  std::size_t size() const { return size_; }

 private:
  const std::byte* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace tellus
