#include "tellus/core/scratch_folder.hpp"

#include <unistd.h>

#include <atomic>
#include <system_error>

#include <fmt/format.h>

#include "tellus/core/atomic_output.hpp"

namespace tellus {
namespace fs = std::filesystem;

Result<ScratchFolder> ScratchFolder::create(const fs::path& parent) {
  std::error_code ec;
  const fs::path base = parent.empty() ? fs::temp_directory_path(ec) : parent;
  if (ec) return makeError("no temporary folder: {}", ec.message());
  removeStaleTemporaries(base);
  static std::atomic<unsigned> counter{0};
  const fs::path path = base / fmt::format("{}{}-{}", kScratchFolderPrefix, ::getpid(), counter++);
  if (!fs::create_directory(path, ec) || ec) {
    return makeError("cannot create a scratch folder in '{}': {}", base.string(),
                     ec ? ec.message() : std::string("it already exists"));
  }
  return ScratchFolder(path);
}

ScratchFolder::ScratchFolder(ScratchFolder&& other) noexcept : path_(std::move(other.path_)) {
  other.path_.clear();
}

ScratchFolder& ScratchFolder::operator=(ScratchFolder&& other) noexcept {
  if (this != &other) {
    std::error_code ec;
    if (!path_.empty()) fs::remove_all(path_, ec);
    path_ = std::move(other.path_);
    other.path_.clear();
  }
  return *this;
}

ScratchFolder::~ScratchFolder() {
  std::error_code ec;
  if (!path_.empty()) fs::remove_all(path_, ec);
}

}  // namespace tellus
