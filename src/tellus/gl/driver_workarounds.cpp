#include "tellus/gl/driver_workarounds.hpp"

#include <cstdlib>
#include <cstring>

#if defined(__x86_64__) || defined(__i386__)
#include <cpuid.h>
#endif

namespace tellus::gl {
namespace {

// True on AMD processors of family 0x19 (Zen 3, Zen 4) or later.
bool isAmdZen3OrLater() {
#if defined(__x86_64__) || defined(__i386__)
  unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
  if (!__get_cpuid(0, &eax, &ebx, &ecx, &edx)) return false;
  char vendor[13] = {};
  std::memcpy(vendor, &ebx, 4);
  std::memcpy(vendor + 4, &edx, 4);
  std::memcpy(vendor + 8, &ecx, 4);
  if (std::strcmp(vendor, "AuthenticAMD") != 0) return false;
  if (!__get_cpuid(1, &eax, &ebx, &ecx, &edx)) return false;
  const unsigned baseFamily = (eax >> 8) & 0xF, extendedFamily = (eax >> 20) & 0xFF;
  const unsigned family = baseFamily == 0xF ? baseFamily + extendedFamily : baseFamily;
  return family >= 0x19;
#else
  return false;
#endif
}

DriverWorkaround decide() {
  const char* off = std::getenv("TELLUS_NO_DRIVER_WORKAROUNDS");
  if (off && std::strcmp(off, "0") != 0) return {};
  if (std::getenv("GALLIUM_OVERRIDE_CPU_CAPS") || !isAmdZen3OrLater()) return {};
  DriverWorkaround w{"GALLIUM_OVERRIDE_CPU_CAPS", "sse4.1",
                     "llvmpipe's AVX2 gathers crash (SIGILL) on AMD Zen 3 and later with LLVM 15"};
  setenv(w.variable, w.value, 0);
  return w;
}

}  // namespace

DriverWorkaround applyDriverWorkarounds() {
  static const DriverWorkaround applied = decide();
  return applied;
}

}  // namespace tellus::gl
