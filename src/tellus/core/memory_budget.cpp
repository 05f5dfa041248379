#include "tellus/core/memory_budget.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <fstream>
#include <string>

#include <fmt/format.h>

namespace tellus {

namespace {

// MemAvailable in bytes, or 0 when /proc/meminfo cannot tell.
std::uint64_t memAvailableBytes() {
  std::ifstream in("/proc/meminfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("MemAvailable:", 0) == 0) {
      return std::strtoull(line.c_str() + 13, nullptr, 10) * 1024;  // in kB
    }
  }
  return 0;
}

}  // namespace

std::uint64_t availableMemoryBytes() {
  std::uint64_t available = memAvailableBytes();
  if (available == 0) available = std::uint64_t(1) << 62;
  if (const char* limit = std::getenv("TELLUS_MEMORY_LIMIT_MB"); limit && *limit) {
    char* end = nullptr;
    const unsigned long long megabytes = std::strtoull(limit, &end, 10);
    if (end && *end == '\0' && megabytes > 0) {
      available = std::min<std::uint64_t>(available, std::uint64_t(megabytes) << 20);
    }
  }
  for (int resource : {RLIMIT_AS, RLIMIT_DATA}) {
    rlimit limit{};
    if (::getrlimit(resource, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
      available = std::min<std::uint64_t>(available, limit.rlim_cur);
    }
  }
  return available;
}

std::string formatByteCount(double bytes) {
  static constexpr std::array<const char*, 6> kUnits = {"KiB", "MiB", "GiB",
                                                        "TiB", "PiB", "EiB"};
  double value = bytes / 1024.0;
  std::size_t unit = 0;
  while (value >= 1024.0 && unit + 1 < kUnits.size()) {
    value /= 1024.0;
    ++unit;
  }
  if (value >= 1024.0) return fmt::format("{:.3g} bytes", bytes);
  if (unit >= 2) return fmt::format("{:.2f} {}", value, kUnits[unit]);
  return fmt::format("{:.1f} {}", value, kUnits[unit]);
}

Status checkMemoryFor(std::string_view what, double bytes, std::string_view wayOut) {
  const double available = double(availableMemoryBytes());
  if (bytes <= available) return {};
  return makeError("{} needs about {} of memory, more than the {} available; {}", what,
                   formatByteCount(bytes), formatByteCount(available), wayOut);
}

}  // namespace tellus
