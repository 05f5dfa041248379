#include "tellus/core/folder_output.hpp"

#include <algorithm>

#include <fcntl.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <span>

#include "tellus/core/atomic_output.hpp"
#include "tellus/core/input_file.hpp"

namespace tellus {

bool isTileNumberName(const std::string& text) {
  return !text.empty() && text.size() <= 10 &&
         std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

namespace fs = std::filesystem;

namespace {

// `path` made absolute and normal, without a trailing separator ("qm/" -> "/cwd/qm").
fs::path absoluteFolder(const fs::path& path) {
  std::error_code ec;
  fs::path absolute = fs::absolute(path, ec).lexically_normal();
  if (absolute.filename().empty() && absolute.has_parent_path() && absolute != absolute.root_path()) {
    absolute = absolute.parent_path();
  }
  return absolute;
}

// True when `inner` is `outer` or lies inside it (both canonical).
bool isWithin(const fs::path& inner, const fs::path& outer) {
  auto i = inner.begin();
  for (auto o = outer.begin(); o != outer.end(); ++o, ++i) {
    if (o->empty()) continue;  // a trailing separator
    if (i == inner.end() || *i != *o) return false;
  }
  return true;
}

Status checkParentWritable(const fs::path& folder, const fs::path& absolute) {
  const fs::path parent = absolute.parent_path();
  std::error_code ec;
  if (!fs::is_directory(parent, ec)) {
    return makeError("cannot write '{}': folder '{}' does not exist", folder.string(), parent.string());
  }
  if (::access(parent.c_str(), W_OK) != 0) {
    return makeError("cannot write '{}': its folder '{}': {}", folder.string(), parent.string(),
                     std::strerror(errno));
  }
  return {};
}

// What is in an existing folder that forbids replacing it; empty when it may be replaced.
std::string whyNotReplaceable(const fs::path& canonical, const FolderOutputKind& kind) {
  std::error_code ec;
  const fs::path cwd = fs::canonical(fs::current_path(ec), ec);
  if (!ec && isWithin(cwd, canonical)) {
    return "it is the current folder or holds it; give a new folder";
  }
  for (const fs::path& input : protectedInputPaths()) {
    std::error_code inputError;
    const fs::path inputCanonical = fs::canonical(input, inputError);
    if (!inputError && (isWithin(inputCanonical, canonical) || inputCanonical.parent_path() == canonical)) {
      return fmt::format("it holds the input '{}'; write the output elsewhere", input.string());
    }
  }
  bool marker = false;
  std::string foreign;
  fs::recursive_directory_iterator it(canonical, fs::directory_options::none, ec);
  if (ec) return fmt::format("its content cannot be listed: {}", ec.message());
  for (; it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (ec) return fmt::format("its content cannot be listed: {}", ec.message());
    const fs::path relative = it->path().lexically_relative(canonical);
    std::error_code typeError;
    const bool link = it->is_symlink(typeError);
    if (relative == kind.markerName && !link && it->is_regular_file(typeError)) {
      marker = true;
    } else if (link || !kind.ownEntry(relative)) {
      foreign = relative.string();
      break;
    }
  }
  if (!foreign.empty()) {
    return fmt::format("it holds '{}', which is not part of {} written by Tellus; give a new or "
                       "empty folder (Tellus replaces only its own output)",
                       foreign, kind.description);
  }
  if (!marker && !fs::is_empty(canonical, ec)) {
    return fmt::format("it has no '{}' marker, so Tellus did not write it; give a new or empty "
                       "folder (Tellus replaces only its own output)",
                       kind.markerName);
  }
  return {};
}

int renameExchange(const fs::path& a, const fs::path& b) {
  return ::renameat2(AT_FDCWD, a.c_str(), AT_FDCWD, b.c_str(), RENAME_EXCHANGE);
}

}  // namespace

Status checkFolderOutput(const fs::path& folder, const FolderOutputKind& kind) {
  if (folder.empty()) return makeError("the output folder's name is empty");
  const fs::path absolute = absoluteFolder(folder);
  if (absolute == absolute.root_path() || absolute.filename() == "." || absolute.filename() == "..") {
    return makeError("cannot write {} into '{}': it is the root or the current folder; give a "
                     "new folder",
                     kind.description, folder.string());
  }
  struct stat info {};
  if (::lstat(absolute.c_str(), &info) != 0) {
    if (errno != ENOENT) {
      return makeError("cannot write {} into '{}': {}", kind.description, folder.string(), std::strerror(errno));
    }
    return checkParentWritable(folder, absolute);
  }
  if (!S_ISDIR(info.st_mode)) {
    return makeError("cannot write {} into '{}': it is {}, not a folder", kind.description,
                     folder.string(), fileKindName(info.st_mode));
  }
  std::error_code ec;
  const fs::path canonical = fs::canonical(absolute, ec);
  if (ec) return makeError("cannot write {} into '{}': {}", kind.description, folder.string(), ec.message());
  if (const std::string why = whyNotReplaceable(canonical, kind); !why.empty()) {
    return makeError("will not replace '{}': {}", folder.string(), why);
  }
  return checkParentWritable(folder, absolute);
}

Result<FolderOutput> FolderOutput::begin(const fs::path& folder, FolderOutputKind kind) {
  if (Status ok = checkFolderOutput(folder, kind); !ok) return ok.error();
  const fs::path absolute = absoluteFolder(folder);
  removeStaleTemporariesFor(absolute);
  const fs::path temporary = temporaryPathFor(absolute);
  std::error_code ec;
  if (!fs::create_directory(temporary, ec) || ec) {
    return makeError("cannot create '{}': {}", temporary.string(),
                     ec ? ec.message() : std::string("it exists"));
  }
  return FolderOutput(absolute, temporary, std::move(kind));
}

FolderOutput::FolderOutput(FolderOutput&& other) noexcept
    : folder_(std::move(other.folder_)),
      temporary_(std::exchange(other.temporary_, fs::path())),
      kind_(std::move(other.kind_)),
      committed_(other.committed_) {}

FolderOutput::~FolderOutput() {
  std::error_code ec;
  if (!committed_ && !temporary_.empty()) fs::remove_all(temporary_, ec);
}

Status FolderOutput::commit() {
  if (committed_) return {};
  if (Status ok = checkFolderOutput(folder_, kind_); !ok) return ok;
  const std::string& text = kind_.markerContent;
  if (Status written = writeBytesChecked(temporary_ / kind_.markerName,
                                         std::as_bytes(std::span(text.data(), text.size())),
                                         folder_ / kind_.markerName);
      !written) {
    return written;
  }
  std::error_code ec;
  const auto failed = [&](int error) {
    return makeError("cannot put the new {} in place at '{}': {}", kind_.description,
                     folder_.string(), std::strerror(error));
  };
  if (!fs::exists(fs::symlink_status(folder_, ec))) {
    // No folder there: a plain rename, refused (not merged) should one appear meanwhile.
    if (::renameat2(AT_FDCWD, temporary_.c_str(), AT_FDCWD, folder_.c_str(), RENAME_NOREPLACE) != 0) {
      if (errno != EINVAL && errno != ENOSYS) return failed(errno);
      if (::rename(temporary_.c_str(), folder_.c_str()) != 0) return failed(errno);
    }
    committed_ = true;
    return {};
  }
  // Swap the two folders in one step; the temporary's name then holds the old one.
  if (renameExchange(temporary_, folder_) == 0) {
    committed_ = true;
    fs::remove_all(temporary_, ec);
    return {};
  }
  if (errno != EINVAL && errno != ENOSYS) return failed(errno);
  // A file system without exchange: set the old folder aside under a name the sweep puts back
  // (removeStaleTemporaries), then rename the new one in.
  const fs::path aside = setAsidePathFor(folder_);
  if (::rename(folder_.c_str(), aside.c_str()) != 0) return failed(errno);
  if (::rename(temporary_.c_str(), folder_.c_str()) != 0) {
    const int error = errno;
    ::rename(aside.c_str(), folder_.c_str());
    return failed(error);
  }
  committed_ = true;
  fs::remove_all(aside, ec);
  return {};
}

}  // namespace tellus
