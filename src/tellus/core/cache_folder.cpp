#include "tellus/core/cache_folder.hpp"

#include <unistd.h>

#include <cctype>
#include <cstdlib>

namespace tellus {
namespace fs = std::filesystem;

namespace {

fs::path userCache(std::string_view kind) {
  const char* xdg = std::getenv("XDG_CACHE_HOME");
  const char* home = std::getenv("HOME");
  std::error_code ec;
  const fs::path base = xdg && *xdg ? fs::path(xdg)
                        : home && *home ? fs::path(home) / ".cache"
                                        : fs::temp_directory_path(ec);
  return base / "tellus" / std::string(kind);
}

}  // namespace

fs::path derivedCacheFolder(const std::string& input, std::string_view suffix, std::string_view kind) {
  if (input.find("://") != std::string::npos) {
    std::string name;
    for (const char c : input) name += std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' ? c : '_';
    return userCache(kind) / (name + std::string(suffix));
  }
  const fs::path beside = fs::absolute(input + std::string(suffix));
  std::error_code ec;
  if (fs::is_directory(beside, ec) ? ::access(beside.c_str(), W_OK) == 0
                                   : ::access(beside.parent_path().c_str(), W_OK) == 0) {
    return beside;
  }
  return userCache(kind);
}

}  // namespace tellus
