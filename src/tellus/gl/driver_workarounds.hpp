#pragma once
// Workarounds for known driver bugs, applied before the first GL context is made (they set
// environment variables the driver reads once, when it loads).
//
// llvmpipe on AMD Zen 3 and later (Debian 12: Mesa 22.3, LLVM 15): the JIT emits AVX2 gathers
// whose destination is also their index register (an encoding the CPU refuses), so drawing the
// CPU-built meshes (ROAM, GAMeR, BDAM...) ends in SIGILL. Seen on an AMD EPYC (family 0x19):
// `vpgatherdd %ymm4,(%rax,%ymm0,1),%ymm0` right after `vxorps %xmm0,%xmm0,%xmm0`. Limiting
// llvmpipe to SSE4.1 (GALLIUM_OVERRIDE_CPU_CAPS=sse4.1) avoids the gathers; frame times on that
// machine were the same within noise (reference renderer, 12 frames, two alternating pairs).
namespace tellus::gl {

// What applyDriverWorkarounds() did, for the log (empty: nothing).
struct DriverWorkaround {
  const char* variable = nullptr;
  const char* value = nullptr;
  const char* reason = nullptr;
};

// Sets the variables above where the machine needs them and the user has not set them already
// (TELLUS_NO_DRIVER_WORKAROUNDS=1 turns this off). Idempotent; the first call decides.
DriverWorkaround applyDriverWorkarounds();

}  // namespace tellus::gl
