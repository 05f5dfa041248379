#pragma once
// Input files that cannot hang or surprise a command: every file Tellus reads (DEMs, tile
// stores, keyframe paths) must be a regular file. A FIFO, a device or a socket would block a
// reader for ever or stream endless bytes, so they are refused with a message before anything
// opens them for reading (a FIFO is opened non-blocking, so even the check cannot hang).
//
// GDAL's virtual file systems (/vsimem/, /vsizip/, /vsicurl/, ...) stream on purpose: paths
// starting with "/vsi" are left to GDAL.
#include <cstddef>
#include <filesystem>
#include <string>

#include "tellus/core/result.hpp"

namespace tellus {

// "a FIFO", "a character device", "a folder", "a symbolic link", "a file"... for messages about
// what a path is (`mode` as stat() gives it).
const char* fileKindName(unsigned mode);

// True for GDAL virtual file system paths ("/vsimem/x.tif").
bool isGdalVirtualPath(const std::filesystem::path& path);

// Succeeds when `path` names an existing regular file (links followed) or a GDAL virtual path.
// Errors: "cannot open 'X': no such file", "... it is a folder", "... it is a FIFO, not a
// regular file".
Status checkRegularInput(const std::filesystem::path& path);

// Opens a regular file for reading without ever blocking (O_NONBLOCK until fstat has shown it
// is a regular file). Returns the file descriptor; the caller closes it.
Result<int> openRegularInput(const std::filesystem::path& path);

// The whole content of a small regular file (keyframe JSON and the like); refuses files over
// `maxBytes` with the size in the message.
Result<std::string> readSmallInputFile(const std::filesystem::path& path, std::size_t maxBytes);

}  // namespace tellus
