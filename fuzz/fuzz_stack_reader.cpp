// libFuzzer target: the .tstack reader (tellus/formats/stacks/stack_file.hpp) on arbitrary file
// contents, in a memfd. The fuzzing build computes but does not compare the checksums, so that
// mutations reach the level table, the block sizes, zstd, the columns and the geometry checks.
// Reading must fail with a message or give levels; those then go through the pyramid check
// verify makes. Tellus' memory budget is 512 MiB (TELLUS_MEMORY_LIMIT_MB), within libFuzzer's
// 2 GiB: a file that declares more must be refused, not allocated.
#include <cstdint>
#include <cstdlib>

#include "fuzz_memfd.hpp"
#include "tellus/formats/stacks/stack_file.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  ::setenv("TELLUS_MEMORY_LIMIT_MB", "512", 1);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = tellus::fuzz::memoryFile(data, size);
  if (path.empty()) return 0;
  tellus::Result<std::vector<tellus::StackTerrain>> levels = tellus::readStackFile(path);
  if (!levels) return 0;
  (void)tellus::verifyStackPyramid(levels.value());
  return 0;
}
