#pragma once
// Fixed-offset fields of a binary header or table held in a byte vector (Tellus's own files:
// the formats of formats/), in the machine's byte order (little-endian on every platform Tellus
// builds for). The caller checks that `at + sizeof(T)` lies within the vector.
#include <cstddef>
#include <cstring>
#include <vector>

namespace tellus {

template <typename T>
void putField(std::vector<std::byte>& out, std::size_t at, T value) {
  std::memcpy(out.data() + at, &value, sizeof(T));
}

template <typename T>
T getField(const std::vector<std::byte>& in, std::size_t at) {
  T value;
  std::memcpy(&value, in.data() + at, sizeof(T));
  return value;
}

}  // namespace tellus
