#include "tellus/core/atomic_output.hpp"

#include <signal.h>
#include <unistd.h>

#include <cctype>
#include <fstream>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <system_error>

#include <fmt/format.h>

namespace tellus {
namespace fs = std::filesystem;

namespace {

fs::path parentOrCurrent(const fs::path& path) {
  return path.has_parent_path() ? path.parent_path() : fs::path(".");
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
  if (fs::is_directory(path, ec)) {
    return makeError("cannot write '{}': it is a folder", path.string());
  }
  return {};
}

Status writeFileAtomically(const fs::path& path,
                           const std::function<Status(const fs::path&)>& write) {
  if (Status writable = checkOutputWritable(path); !writable) return writable;
  static std::atomic<unsigned> counter{0};
  const fs::path temp =
      parentOrCurrent(path) /
      fmt::format(".{}.tmp-{}-{}", path.filename().string(), ::getpid(), counter++);
  Status status = write(temp);
  std::error_code ec;
  if (status) {
    fs::rename(temp, path, ec);
    if (ec) status = makeError("cannot write '{}': {}", path.string(), ec.message());
  }
  if (!status) fs::remove(temp, ec);
  return status;
}

Status writeTextFileAtomically(const std::filesystem::path& path, std::string_view text) {
  return writeFileAtomically(path, [&](const std::filesystem::path& temp) -> Status {
    std::ofstream out(temp, std::ios::binary);
    out.write(text.data(), std::streamsize(text.size()));
    out.close();
    if (!out) return makeError("cannot write '{}'", path.string());
    return {};
  });
}

void removeStaleTemporaries(const std::filesystem::path& folder, std::string_view prefix) {
  std::error_code ec;
  for (const std::filesystem::directory_entry& entry :
       std::filesystem::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    std::size_t digits = prefix.size();
    while (digits < name.size() && std::isdigit(static_cast<unsigned char>(name[digits]))) ++digits;
    if (digits == prefix.size()) continue;
    const long pid = std::stol(name.substr(prefix.size(), digits - prefix.size()));
    if (::kill(pid_t(pid), 0) != 0 && errno == ESRCH) std::filesystem::remove(entry.path(), ec);
  }
}

}  // namespace tellus
