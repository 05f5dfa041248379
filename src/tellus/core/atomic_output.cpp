#include "tellus/core/atomic_output.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <mutex>
#include <set>
#include <system_error>
#include <utility>

#include <fmt/format.h>

#include "tellus/core/input_file.hpp"

namespace tellus {
namespace fs = std::filesystem;

namespace {

constexpr std::string_view kTemporaryTag = ".tellus-partial-";
constexpr std::string_view kPreviousTag = ".tellus-previous-";

fs::path parentOrCurrent(const fs::path& path) {
  return path.has_parent_path() ? path.parent_path() : fs::path(".");
}

// Device and inode of the files the running command reads.
struct ProtectedInputs {
  std::mutex mutex;
  std::set<std::pair<dev_t, ino_t>> identities;
  std::vector<fs::path> names;  // parallel to insertion, for messages
};

ProtectedInputs& protectedInputs() {
  static ProtectedInputs inputs;
  return inputs;
}

// The protected input `path` is (same device and inode), or an empty path.
fs::path protectedInputAt(const fs::path& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) return {};
  ProtectedInputs& inputs = protectedInputs();
  std::lock_guard lock(inputs.mutex);
  if (!inputs.identities.count({info.st_dev, info.st_ino})) return {};
  for (const fs::path& name : inputs.names) {
    struct stat other {};
    if (::stat(name.c_str(), &other) == 0 && other.st_dev == info.st_dev &&
        other.st_ino == info.st_ino) {
      return name;
    }
  }
  return path;
}

}  // namespace

Status checkOutputWritable(const fs::path& path) {
  if (path.empty()) return makeError("output path is empty");
  const fs::path folder = parentOrCurrent(path);
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) {
    return makeError("cannot write '{}': folder '{}' does not exist", path.string(),
                     folder.string());
  }
  if (::access(folder.c_str(), W_OK) != 0) {
    return makeError("cannot write '{}': {}", path.string(), std::strerror(errno));
  }
  struct stat info {};
  if (::stat(path.c_str(), &info) == 0) {
    if (S_ISDIR(info.st_mode)) return makeError("cannot write '{}': it is a folder", path.string());
    if (!S_ISREG(info.st_mode)) {
      return makeError(
          "cannot write '{}': it is {}; Tellus writes regular files only (it would replace it)",
          path.string(), fileKindName(info.st_mode));
    }
    if (const fs::path input = protectedInputAt(path); !input.empty()) {
      return makeError("cannot write '{}': it is the input '{}'; write the output elsewhere",
                       path.string(), input.string());
    }
  }
  return {};
}

void protectInputFiles(const std::vector<fs::path>& inputs) {
  ProtectedInputs& registry = protectedInputs();
  std::lock_guard lock(registry.mutex);
  for (const fs::path& input : inputs) {
    struct stat info {};
    if (::stat(input.c_str(), &info) != 0) continue;
    registry.identities.insert({info.st_dev, info.st_ino});
    registry.names.push_back(input);
  }
}

void clearProtectedInputFiles() {
  ProtectedInputs& registry = protectedInputs();
  std::lock_guard lock(registry.mutex);
  registry.identities.clear();
  registry.names.clear();
}

std::vector<fs::path> protectedInputPaths() {
  ProtectedInputs& registry = protectedInputs();
  std::lock_guard lock(registry.mutex);
  return registry.names;
}

namespace {
std::atomic<unsigned> temporaryCounter{0};
}  // namespace

bool processExists(long pid) {
  if (pid <= 0) return false;
  if (::kill(pid_t(pid), 0) != 0 && errno == ESRCH) return false;
  // A killed process whose parent died too (`timeout -s KILL` kills its own process group)
  // waits as a zombie until init reaps it, which can take seconds: dead all the same.
  std::ifstream stat(fmt::format("/proc/{}/stat", pid));
  std::string text((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
  const std::size_t close = text.rfind(')');  // the name may hold spaces and parentheses
  if (close != std::string::npos && close + 2 < text.size()) {
    const char state = text[close + 2];
    if (state == 'Z' || state == 'X' || state == 'x') return false;
  }
  return true;
}

fs::path temporaryPathFor(const fs::path& destination) {
  return parentOrCurrent(destination) / fmt::format(".{}{}{}-{}", destination.filename().string(),
                                                    kTemporaryTag, ::getpid(), temporaryCounter++);
}

fs::path setAsidePathFor(const fs::path& destination) {
  return parentOrCurrent(destination) / fmt::format(".{}{}{}-{}", destination.filename().string(),
                                                    kPreviousTag, ::getpid(), temporaryCounter++);
}

void removeStaleTemporariesFor(const fs::path& destination) {
  removeStaleTemporaries(parentOrCurrent(destination));
}

Status writeFileAtomically(const fs::path& path,
                           const std::function<Status(const fs::path&)>& write) {
  if (Status writable = checkOutputWritable(path); !writable) return writable;
  removeStaleTemporariesFor(path);
  const fs::path temp = temporaryPathFor(path);
  Status status = write(temp);
  std::error_code ec;
  if (status) {
    // Checked again: the destination may have changed while the output was made.
    if (Status writable = checkOutputWritable(path); !writable) status = writable;
  }
  if (status) {
    fs::rename(temp, path, ec);
    if (ec) status = makeError("cannot write '{}': {}", path.string(), ec.message());
  }
  if (!status) fs::remove(temp, ec);
  return status;
}

Status writeBytesChecked(const fs::path& path, std::span<const std::byte> bytes,
                         const fs::path& reportedName) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return makeError("cannot write '{}': {}", reportedName.string(), std::strerror(errno));
  const auto failed = [&](int error) -> Status {
    ::close(fd);
    return makeError("cannot write '{}': {}", reportedName.string(), std::strerror(error));
  };
  const std::byte* p = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return failed(errno);
    if (n == 0) return failed(EIO);
    p += n;
    left -= std::size_t(n);
  }
  // Delayed allocation: some file systems report a full disk only here.
  if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) return failed(errno);
  if (::close(fd) != 0) {
    return makeError("cannot write '{}': {}", reportedName.string(), std::strerror(errno));
  }
  return {};
}

Status writeBytesAtomically(const fs::path& path, std::span<const std::byte> bytes) {
  return writeFileAtomically(
      path, [&](const fs::path& temp) { return writeBytesChecked(temp, bytes, path); });
}

Status writeTextFileAtomically(const fs::path& path, std::string_view text) {
  return writeBytesAtomically(path, std::as_bytes(std::span(text.data(), text.size())));
}

void removeStaleTemporaries(const fs::path& folder) {
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    // ".tellus-scratch-PID-N", ".NAME.tellus-partial-PID-N" or ".NAME.tellus-previous-PID-N":
    // the PID follows the tag.
    std::size_t digits = std::string::npos;
    std::string previousOf;  // NAME, for a folder set aside while being replaced
    if (name.starts_with(kScratchFolderPrefix)) {
      digits = kScratchFolderPrefix.size();
    } else if (name.starts_with(".")) {
      const std::size_t tag = name.rfind(kTemporaryTag);
      const std::size_t previous = name.rfind(kPreviousTag);
      if (tag != std::string::npos) {
        digits = tag + kTemporaryTag.size();
      } else if (previous != std::string::npos && previous > 1) {
        digits = previous + kPreviousTag.size();
        previousOf = name.substr(1, previous - 1);
      }
    }
    if (digits == std::string::npos) continue;
    std::size_t end = digits;
    while (end < name.size() && std::isdigit(static_cast<unsigned char>(name[end]))) ++end;
    if (end == digits || end - digits > 9) continue;
    const long pid = std::stol(name.substr(digits, end - digits));
    if (pid <= 0 || processExists(pid)) continue;
    if (!previousOf.empty() && !fs::exists(fs::symlink_status(folder / previousOf, ec))) {
      fs::rename(entry.path(), folder / previousOf, ec);  // put the old folder back
    } else {
      fs::remove_all(entry.path(), ec);
    }
  }
}

}  // namespace tellus
