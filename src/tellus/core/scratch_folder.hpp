#pragma once
// A private folder for temporary files (GDAL's work files, on-disk scratch copies): created
// as ".tellus-scratch-PID-N" inside a parent folder, removed with everything in it when the
// ScratchFolder is destroyed. Folders of processes that no longer exist (killed runs) are
// removed whenever a new one is created in the same parent, so nothing is left for ever.
#include <filesystem>

#include "tellus/core/result.hpp"

namespace tellus {

class ScratchFolder {
 public:
  // In `parent` (the system's temporary folder when empty).
  static Result<ScratchFolder> create(const std::filesystem::path& parent = {});
  ScratchFolder(ScratchFolder&& other) noexcept;
  ScratchFolder& operator=(ScratchFolder&& other) noexcept;
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  ~ScratchFolder();

  const std::filesystem::path& path() const { return path_; }

 private:
  explicit ScratchFolder(std::filesystem::path path) : path_(std::move(path)) {}
  std::filesystem::path path_;
};

}  // namespace tellus
