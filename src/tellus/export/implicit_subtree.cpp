#include "tellus/export/implicit_subtree.hpp"

#include <algorithm>
#include <cstring>

#include <nlohmann/json.hpp>

namespace tellus {

std::uint64_t quadtreeMortonIndex(std::uint32_t x, std::uint32_t y) {
  std::uint64_t index = 0;
  for (int bit = 0; bit < 32; ++bit) {
    index |= std::uint64_t((x >> bit) & 1u) << (2 * bit);
    index |= std::uint64_t((y >> bit) & 1u) << (2 * bit + 1);
  }
  return index;
}

QuadtreeSubtreeAvailability emptySubtreeAvailability(int levels) {
  QuadtreeSubtreeAvailability a;
  a.levels = std::clamp(levels, 1, 12);
  const std::size_t below = std::size_t(1) << (2 * a.levels);  // 4^levels
  a.tiles.assign((below - 1) / 3, false);
  a.children.assign(below, false);
  return a;
}

std::size_t subtreeTileBit(int depth, std::uint32_t x, std::uint32_t y) {
  return ((std::size_t(1) << (2 * depth)) - 1) / 3 + std::size_t(quadtreeMortonIndex(x, y));
}

namespace {

// The JSON of one availability (a constant, or a bitstream appended to `binary` as a new
// buffer view).
nlohmann::json availabilityJson(const std::vector<bool>& bits, std::string& binary,
                                nlohmann::json& bufferViews) {
  const std::size_t available = std::size_t(std::count(bits.begin(), bits.end(), true));
  if (available == 0) return {{"constant", 0}};
  if (available == bits.size()) return {{"constant", 1}};
  while (binary.size() % 8 != 0) binary.push_back('\0');
  const std::size_t offset = binary.size();
  const std::size_t length = (bits.size() + 7) / 8;
  binary.resize(offset + length, '\0');
  for (std::size_t i = 0; i < bits.size(); ++i) {
    if (bits[i]) binary[offset + i / 8] = char(std::uint8_t(binary[offset + i / 8]) | (1u << (i % 8)));
  }
  bufferViews.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}});
  return {{"bitstream", bufferViews.size() - 1}, {"availableCount", available}};
}

void putUint(std::string& out, std::uint64_t value, int bytes) {
  for (int i = 0; i < bytes; ++i) out.push_back(char((value >> (8 * i)) & 0xffu));
}

}  // namespace

std::string encodeSubtree(const QuadtreeSubtreeAvailability& availability) {
  std::string binary;
  nlohmann::json bufferViews = nlohmann::json::array();
  nlohmann::json subtree;
  subtree["tileAvailability"] = availabilityJson(availability.tiles, binary, bufferViews);
  if (availability.contentEverywhereTilesAre) {
    // The same bitstream (or constant) as the tiles'.
    subtree["contentAvailability"] = nlohmann::json::array({subtree["tileAvailability"]});
  }
  subtree["childSubtreeAvailability"] = availabilityJson(availability.children, binary, bufferViews);
  while (binary.size() % 8 != 0) binary.push_back('\0');
  if (!binary.empty()) {
    subtree["buffers"] = nlohmann::json::array({{{"byteLength", binary.size()}}});
    subtree["bufferViews"] = bufferViews;
  }
  std::string json = subtree.dump();
  while (json.size() % 8 != 0) json.push_back(' ');
  std::string out = "subt";
  putUint(out, 1, 4);
  putUint(out, json.size(), 8);
  putUint(out, binary.size(), 8);
  out += json;
  out += binary;
  return out;
}

}  // namespace tellus
