#pragma once
// Output files that appear complete or not at all: write to a temporary file in the same
// folder, then rename over the destination. A failed or interrupted write leaves no file at
// the destination (and removes the temporary when it can).
#include <filesystem>
#include <functional>
#include <string_view>

#include "tellus/core/result.hpp"

namespace tellus {

// Checks, before any expensive work, that `path` can be created: its folder exists and is
// writable, and `path` is not a folder.
Status checkOutputWritable(const std::filesystem::path& path);

// Calls write(tempPath) and renames tempPath to `path` when it succeeds.
Status writeFileAtomically(const std::filesystem::path& path,
                           const std::function<Status(const std::filesystem::path&)>& write);

// Writes `text` to `path` atomically, flushed and checked (a full disk is an error, not a
// truncated file).
Status writeTextFileAtomically(const std::filesystem::path& path, std::string_view text);

// Removes files in `folder` named PREFIX<pid><anything> whose process <pid> no longer exists:
// temporaries left behind by a killed process. Files of live processes are kept.
void removeStaleTemporaries(const std::filesystem::path& folder, std::string_view prefix);

}  // namespace tellus
