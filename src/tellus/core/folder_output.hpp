#pragma once
// Output folders that appear whole or not at all, and never replace what Tellus did not write
// (a tile set of thousands of files: `tellus export --quantized-mesh DIR`).
//
// The folder is written as a temporary beside the destination (".NAME.tellus-partial-PID-N",
// swept by removeStaleTemporaries() when its process is dead), then swapped in with one
// atomic renameat2(RENAME_EXCHANGE) and the old content removed afterwards: a kill at any
// moment leaves either the old folder or the new one at DIR, never neither.
//
// An existing DIR is replaced only when
//   - it is a real folder (not a symbolic link, device, FIFO or file),
//   - it is not the current folder nor one of its parents, nor the folder of any input,
//   - it holds no input of the running command (protectInputFiles()),
//   - and it is empty, or it holds Tellus's marker file and nothing but the entries this kind
//     of output consists of (ownEntry says which relative paths those are).
// Anything else is refused with the first foreign entry named.
#include <filesystem>
#include <functional>
#include <string>

#include "tellus/core/result.hpp"

namespace tellus {

struct FolderOutputKind {
  // What the folder holds, for messages ("a quantized-mesh tile set").
  std::string description;
  // The marker's file name inside the folder (".tellus-tileset") and its content.
  std::string markerName;
  std::string markerContent;
  // True for a relative path (files and folders, '/'-separated) a folder of this kind may
  // hold besides the marker.
  std::function<bool(const std::filesystem::path&)> ownEntry;
};

// Whether a path component is a tile number as tile sets name them ("0".."9999999999"): what a
// FolderOutputKind::ownEntry of a tile set accepts for its Z, X and Y parts.
bool isTileNumberName(const std::string& text);

// Checks, before any work, that `folder` may be written or replaced (rules above) and that
// its parent exists and is writable. Errors name the folder and why, and what to do.
Status checkFolderOutput(const std::filesystem::path& folder, const FolderOutputKind& kind);

// A folder being written: begin() makes the temporary, commit() writes the marker and swaps it
// in, and the destructor removes the temporary of a folder never committed.
class FolderOutput {
 public:
  static Result<FolderOutput> begin(const std::filesystem::path& folder, FolderOutputKind kind);
  FolderOutput(FolderOutput&& other) noexcept;
  FolderOutput& operator=(FolderOutput&&) = delete;
  FolderOutput(const FolderOutput&) = delete;
  FolderOutput& operator=(const FolderOutput&) = delete;
  ~FolderOutput();

  // Where to write the folder's content.
  const std::filesystem::path& temporary() const { return temporary_; }
  // Checks the destination again (it may have changed meanwhile), writes the marker and puts
  // the new folder in place; the old one, if any, is removed after the swap.
  Status commit();

 private:
  FolderOutput(std::filesystem::path folder, std::filesystem::path temporary, FolderOutputKind kind)
      : folder_(std::move(folder)), temporary_(std::move(temporary)), kind_(std::move(kind)) {}
  std::filesystem::path folder_, temporary_;
  FolderOutputKind kind_;
  bool committed_ = false;
};

}  // namespace tellus
