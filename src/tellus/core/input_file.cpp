#include "tellus/core/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <algorithm>
#include <cctype>
#include <cstring>
#include <map>
#include <string>

#include <fmt/format.h>

namespace tellus {
namespace fs = std::filesystem;

const char* fileKindName(unsigned mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISLNK(mode)) return "a symbolic link";
  if (S_ISREG(mode)) return "a file";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

namespace {

// For a folder given where files are wanted: the pattern of the data files it holds
// ("DIR/*.hgt (16 files)"), by the commonest extension of the rasters and stores Tellus reads.
std::string folderSuggestion(const fs::path& folder) {
  static const char* const kKnown[] = {".hgt", ".tif", ".tiff", ".bil", ".asc", ".img", ".dem",
                                       ".png", ".jpg", ".tstore", ".tstack", ".vrt", ".nc"};
  std::map<std::string, int> counts;
  std::error_code ec;
  int seen = 0;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end && seen < 10000; it.increment(ec), ++seen) {
    std::string extension = it->path().extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    if (std::find(std::begin(kKnown), std::end(kKnown), extension) != std::end(kKnown)) ++counts[extension];
  }
  const auto best = std::max_element(counts.begin(), counts.end(),
                                     [](const auto& a, const auto& b) { return a.second < b.second; });
  if (best == counts.end()) return "give the files in it";
  return fmt::format("give the files in it: '{}' ({} file{})", (folder / ("*" + best->first)).string(),
                     best->second, best->second == 1 ? "" : "s");
}

Status describeNonRegular(const fs::path& path, mode_t mode) {
  if (S_ISDIR(mode)) {
    return makeError("cannot open '{}': it is a folder; {}", path.string(), folderSuggestion(path));
  }
  return makeError("cannot open '{}': it is {}, not a regular file", path.string(),
                   fileKindName(mode));
}

}  // namespace

bool isGdalVirtualPath(const fs::path& path) {
  return path.native().rfind("/vsi", 0) == 0;
}

Status checkRegularInput(const fs::path& path) {
  if (path.empty()) return makeError("an input path is empty");
  if (isGdalVirtualPath(path)) return {};
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) {
    if (errno == ENOENT) return makeError("cannot open '{}': no such file", path.string());
    return makeError("cannot open '{}': {}", path.string(), std::strerror(errno));
  }
  if (!S_ISREG(info.st_mode)) return describeNonRegular(path, info.st_mode);
  return {};
}

Result<int> openRegularInput(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    if (errno == ENOENT) return makeError("cannot open '{}': no such file", path.string());
    return makeError("cannot open '{}': {}", path.string(), std::strerror(errno));
  }
  struct stat info {};
  if (::fstat(fd, &info) != 0) {
    const int error = errno;
    ::close(fd);
    return makeError("cannot open '{}': {}", path.string(), std::strerror(error));
  }
  if (!S_ISREG(info.st_mode)) {
    ::close(fd);
    return describeNonRegular(path, info.st_mode).error();
  }
  // Regular files never block; clear the flag so reads behave as usual.
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  return fd;
}

Result<std::string> readSmallInputFile(const fs::path& path, std::size_t maxBytes) {
  Result<int> opened = openRegularInput(path);
  if (!opened) return opened.error();
  const int fd = opened.value();
  struct stat info {};
  ::fstat(fd, &info);
  if (std::uint64_t(info.st_size) > maxBytes) {
    ::close(fd);
    return makeError("'{}' is {} bytes; at most {} bytes are expected here", path.string(),
                     info.st_size, maxBytes);
  }
  std::string text(std::size_t(info.st_size), '\0');
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::read(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += std::size_t(n);
  }
  ::close(fd);
  text.resize(done);
  return text;
}

}  // namespace tellus
