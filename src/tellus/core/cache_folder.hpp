#pragma once
// Where a command keeps what it derives from an input once and reuses (converted textures,
// imagery pyramids): beside a local input (INPUT + suffix) when that folder may be written, else
// in the user's cache ($XDG_CACHE_HOME or ~/.cache, else the temporary folder) under
// tellus/<kind>/. An input read over HTTP (a URL) always uses the user's cache, in a folder named
// after the URL, never a path made of the URL under the current directory.
#include <filesystem>
#include <string>
#include <string_view>

namespace tellus {

std::filesystem::path derivedCacheFolder(const std::string& input, std::string_view suffix,
                                         std::string_view kind);

}  // namespace tellus
