// libFuzzer target: BDAM's patch file reader (tellus/formats/bdam/bdam_file.hpp) on arbitrary file
// contents, in a memfd. The fuzzing build computes but does not compare the checksums (header,
// table, patches), so that mutations reach the table's and the patches' value checks. Opening
// must fail with a message or succeed; then every patch (the first 256) is read, which must give
// vertices on the grid and indices among them, or a message.
#include <cstdint>
#include <cstdlib>

#include "fuzz_memfd.hpp"
#include "tellus/formats/bdam/bdam_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = tellus::fuzz::memoryFile(data, size);
  if (path.empty()) return 0;
  tellus::Result<tellus::bdam::PatchFile> file = tellus::bdam::PatchFile::open(path);
  if (!file) return 0;
  static std::vector<tellus::bdam::PackedVertex> vertices;
  static std::vector<std::uint16_t> indices;
  const std::size_t count = std::min<std::size_t>(file->entries().size(), 256);
  for (std::size_t i = 0; i < count; ++i) {
    const tellus::bdam::PatchEntry& e = file->entries()[i];
    if (!file->read(i, vertices, indices)) continue;
    // What a successful read promises the renderer.
    for (std::uint16_t index : indices) {
      if (index >= vertices.size()) std::abort();
    }
    for (const tellus::bdam::PackedVertex& v : vertices) {
      if (!(v.heightM >= e.minZ && v.heightM <= e.maxZ) ||
          e.origin.x + std::uint64_t(v.x) >= std::uint64_t(file->gridWidth()) ||
          e.origin.y + std::uint64_t(v.y) >= std::uint64_t(file->gridHeight())) {
        std::abort();
      }
    }
  }
  return 0;
}
