#pragma once
// The fuzzer's bytes as a file without touching the disk: a memfd (a regular file in memory)
// rewritten for every input, read by path (/proc/self/fd/N) like any file a user gives.
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <string>

namespace tellus::fuzz {

// The path of a memfd holding exactly `data`; empty when it cannot be written.
inline const std::string& memoryFile(const std::uint8_t* data, std::size_t size) {
  static const int fd = ::memfd_create("tellus-fuzz", 0);
  static const std::string path = "/proc/self/fd/" + std::to_string(fd);
  static const std::string none;
  if (fd < 0 || ::ftruncate(fd, 0) != 0 || ::pwrite(fd, data, size, 0) != ssize_t(size)) return none;
  return path;
}

}  // namespace tellus::fuzz
