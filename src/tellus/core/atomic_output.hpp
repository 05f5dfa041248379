#pragma once
// Output files that appear complete or not at all: write to a temporary file in the same
// folder, then rename over the destination. A failed or interrupted write leaves no file at
// the destination (and removes the temporary when it can); a temporary left by a killed
// process is recognisable by its name (".NAME.tellus-partial-PID-N") and is removed by the next
// write of the same destination.
//
// Outputs never replace what they must not: an existing destination must be a regular file (a
// device such as /dev/null or /dev/full would be replaced by a file and a full device would go
// unnoticed), and never a file the running command reads (protectInputFiles()).
#include <cstddef>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "tellus/core/result.hpp"

namespace tellus {

// Checks, before any expensive work, that `path` can be created: its folder exists and is
// writable, `path` is not a folder, not a device or FIFO, and not a protected input.
Status checkOutputWritable(const std::filesystem::path& path);

// Registers the files the running command reads: checkOutputWritable() (and so every writer
// of this library) refuses to write over any of them, whatever name it is given by (the test
// is on the file's identity, device and inode, not its name). Paths that do not exist are
// ignored. Process-wide; thread-safe.
void protectInputFiles(const std::vector<std::filesystem::path>& inputs);
// Forgets every protected input (tests).
void clearProtectedInputFiles();
// The names the protected inputs were registered by (folder outputs check that none lies
// inside the folder they replace).
std::vector<std::filesystem::path> protectedInputPaths();

// True while process `pid` runs (a zombie, killed and not yet reaped, does not count): whose
// temporaries may still be in use.
bool processExists(long pid);

// The name a temporary for `destination` gets: ".NAME.tellus-partial-PID-N" beside it.
std::filesystem::path temporaryPathFor(const std::filesystem::path& destination);
// The name a folder being replaced is set aside under: ".NAME.tellus-previous-PID-N" beside it.
std::filesystem::path setAsidePathFor(const std::filesystem::path& destination);
// Removes, in `destination`'s folder, the temporaries and scratch folders of processes that no
// longer exist (removeStaleTemporaries()).
void removeStaleTemporariesFor(const std::filesystem::path& destination);

// The name scratch folders start with: ".tellus-scratch-PID-N".
inline constexpr std::string_view kScratchFolderPrefix = ".tellus-scratch-";

// Calls write(tempPath) and renames tempPath to `path` when it succeeds.
Status writeFileAtomically(const std::filesystem::path& path,
                           const std::function<Status(const std::filesystem::path&)>& write);

// Writes `bytes` to a new file `path` (not atomically: writers pass their temporary), checking
// every write and the final flush to disk, so a full disk (ENOSPC) or a file size limit is an
// error naming `reportedName`, never a truncated file reported as written.
Status writeBytesChecked(const std::filesystem::path& path, std::span<const std::byte> bytes,
                         const std::filesystem::path& reportedName);

// Writes `text` to `path` atomically, flushed and checked (a full disk is an error, not a
// truncated file).
Status writeTextFileAtomically(const std::filesystem::path& path, std::string_view text);
// The same for bytes.
Status writeBytesAtomically(const std::filesystem::path& path, std::span<const std::byte> bytes);

// Removes the temporaries Tellus leaves in `folder` when a process is killed: files and folders
// ".NAME.tellus-partial-PID-N" and scratch folders ".tellus-scratch-PID-N" (with their content)
// whose process PID no longer exists. Those of live processes are kept. A folder set aside
// while being replaced (".NAME.tellus-previous-PID-N", folder_output.hpp) is put back at NAME
// when nothing is there (the process died between the two renames), else removed.
void removeStaleTemporaries(const std::filesystem::path& folder);

}  // namespace tellus
