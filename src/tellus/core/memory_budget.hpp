#pragma once
// Refusing work that cannot fit in memory before allocating it: a command estimates what it
// is about to allocate and calls checkMemoryFor(), which compares the estimate with the memory
// this process can still get (MemAvailable from /proc/meminfo, capped by RLIMIT_AS / RLIMIT_DATA
// when they are set, and by the environment variable TELLUS_MEMORY_LIMIT_MB when it is: a user
// sharing a machine, or a fuzzer, can give Tellus less). The error gives both figures and the
// way out, instead of std::bad_alloc half way through.
#include <cstdint>
#include <string>
#include <string_view>

#include "tellus/core/result.hpp"

namespace tellus {

// Bytes this process can still allocate, as far as the system says (never 0: when nothing can
// be read, a large figure that lets every request through).
std::uint64_t availableMemoryBytes();

// Fails when `bytes` (an estimate; doubles so that products of absurd sizes cannot overflow)
// exceed availableMemoryBytes(): "<what> needs about 37.3 GiB of memory, more than the 21.9 GiB
// available; <wayOut>".
Status checkMemoryFor(std::string_view what, double bytes, std::string_view wayOut);

// "12.7 MiB", "1.23 GiB", "18.0 KiB", "3.4 EiB".
std::string formatByteCount(double bytes);

}  // namespace tellus
